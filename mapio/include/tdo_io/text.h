/**
 * @file text.h
 * @brief Text from a file made safe to print in one error line: control characters and bytes
 *        outside printable ASCII escaped, the length capped.
 */
#ifndef TDO_IO_TEXT_H
#define TDO_IO_TEXT_H

#include <cstddef>
#include <string>
#include <string_view>

namespace tdo_io {

/** Bytes of a file's text that error messages quote at most (then "... (N bytes)"). */
constexpr std::size_t kQuoteMax = 64;

/** Characters of a whole error line the tools print at most. */
constexpr std::size_t kLineMax = 1024;

/**
 * @brief `text` with every byte outside printable ASCII (0x20..0x7e) written as \xNN and a
 *        backslash as \\; longer than `max` bytes: the first `max` bytes, then "... (N bytes)".
 */
std::string printable(std::string_view text, std::size_t max = kQuoteMax);

/**
 * @brief An error line safe to print: control bytes (< 0x20, 0x7f) written as \xNN, the rest kept
 *        (quotes inside it are already printable()); longer than `max`: cut, then "... (N bytes)".
 */
std::string one_line(std::string_view text, std::size_t max = kLineMax);

}  // namespace tdo_io

#endif  // TDO_IO_TEXT_H
