// Command-line conventions of the host tools (docs/design.md s.10): exit status 0 done, 1 failed
// (the tool says what), 2 bad input. Bad input is thrown as BadInput anywhere below main and
// printed once as "NAME: error: MESSAGE" on stderr.
#ifndef TDO_TOOLS_CLI_TOOL_CLI_H
#define TDO_TOOLS_CLI_TOOL_CLI_H

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

namespace tdo_tool {

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitBadInput = 2;

/** Bad input: the message of the one error line; the tool exits with status 2. */
struct BadInput {
  std::string message;
};

/**
 * Parses argv into `app`. Returns -1 to go on, or the exit status after --help / --help-all
 * printed their text (0). A parse error throws BadInput with CLI11's message.
 */
inline int parse_args(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    throw BadInput{e.what()};
  }
  return -1;
}

/**
 * The tool's main: returns run(argc, argv); BadInput and any other exception become one line
 * "name: error: ..." on stderr (after what the tool printed so far) and exit status 2.
 */
template <typename Run>
int guarded_main(const char* name, Run run, int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const BadInput& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "%s: error: %s\n", name, e.message.c_str());
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "%s: error: %s\n", name, e.what());
  }
  return kExitBadInput;
}

}  // namespace tdo_tool

#endif  // TDO_TOOLS_CLI_TOOL_CLI_H
