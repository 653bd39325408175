# Cross toolchain: bare-metal Cortex-M7 with the double-precision FPU (STM32H7 class), hard float,
# Thumb-2, GNU Arm Embedded (Debian: gcc-arm-none-eabi, libnewlib-arm-none-eabi).
#
#   cmake -S embedded -B build-arm -G Ninja \
#         -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/arm-none-eabi-cortex-m7.cmake
#
# Code generation matches the host build's determinism rules (cmake/TdoWarnings.cmake):
# -ffp-contract=off, so no multiply-add is fused on either side and doubles round the same way.
# No exceptions, no RTTI, no unwind tables; one section per function and object so the linker can
# drop what the image does not use.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR cortex-m7)

set(TDO_ARM_PREFIX "arm-none-eabi-" CACHE STRING "Prefix of the cross tools")
find_program(CMAKE_C_COMPILER ${TDO_ARM_PREFIX}gcc REQUIRED)
find_program(CMAKE_CXX_COMPILER ${TDO_ARM_PREFIX}g++ REQUIRED)
find_program(CMAKE_ASM_COMPILER ${TDO_ARM_PREFIX}gcc REQUIRED)
find_program(CMAKE_OBJCOPY ${TDO_ARM_PREFIX}objcopy REQUIRED)
find_program(CMAKE_SIZE ${TDO_ARM_PREFIX}size REQUIRED)
find_program(CMAKE_NM ${TDO_ARM_PREFIX}nm REQUIRED)

# The compiler checks link a test program; there is no OS to link against, so check a library.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(TDO_ARM_CPU_FLAGS "-mcpu=cortex-m7 -mfpu=fpv5-d16 -mfloat-abi=hard -mthumb")
set(TDO_ARM_COMMON_FLAGS
    "${TDO_ARM_CPU_FLAGS} -ffp-contract=off -ffunction-sections -fdata-sections -fno-common")
set(CMAKE_C_FLAGS_INIT "${TDO_ARM_COMMON_FLAGS}")
set(CMAKE_CXX_FLAGS_INIT
    "${TDO_ARM_COMMON_FLAGS} -fno-exceptions -fno-rtti -fno-unwind-tables -fno-asynchronous-unwind-tables")
set(CMAKE_ASM_FLAGS_INIT "${TDO_ARM_CPU_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${TDO_ARM_CPU_FLAGS} -Wl,--gc-sections")

# Search the host only for programs; headers and libraries come from the cross sysroot.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
