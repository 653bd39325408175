# tdo_set_warnings(target): the warnings every project target builds with (errors in CI).
option(TDO_WERROR "Treat warnings as errors" OFF)
function(tdo_set_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wdouble-promotion -Wfloat-equal -Wconversion
    -Wno-sign-conversion -Wcast-align -Wnull-dereference)
  if(TDO_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
# Library code additionally: no exceptions, no RTTI, no FMA contraction (determinism), and no
# errno from the math functions: the library never reads errno, so sqrt and friends compile to the
# bare instruction (the same IEEE results, without a branch and an out-of-line call around each).
function(tdo_set_library_flags target)
  tdo_set_warnings(${target})
  target_compile_options(${target} PRIVATE $<$<COMPILE_LANGUAGE:CXX>:-fno-exceptions -fno-rtti>
                         -ffp-contract=off -fno-math-errno)
endfunction()
