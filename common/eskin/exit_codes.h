// The exit codes of the eskin program: one table, read by the CLI (main.cpp
// maps errors onto it, `eskin --help` prints it), by docs/guide.md ("Exit
// codes", checked against this list by tests/system/exit_codes_test.cpp)
// and by the commands that end with a specific verdict.
#pragma once

namespace eskin {

// X(name, code, meaning)
#define ESKIN_EXIT_CODES(X)                                                                      \
  X(ok, 0, "success (also --help)")                                                              \
  X(failure, 1, "the run failed: a tool, a file, the link, or a check it ran (regression, "      \
                "mismatch)")                                                                     \
  X(usage, 2, "bad input: the command line, a scene or configuration file, an argument value")   \
  X(rejected, 3, "eskin config: the board rejected the command (the reason is printed)")         \
  X(no_verdict, 4, "eskin config: no verdict came back within --timeout-ms")                     \
  X(no_packets, 5, "eskin stream: bytes arrived but no packet decoded (wrong baud rate?)")       \
  X(port_held, 6, "the serial port is held by another eskin process (its pid is printed)")

enum class Exit : int {
#define ESKIN_EXIT_ENUM(name, code, meaning) name = code,
  ESKIN_EXIT_CODES(ESKIN_EXIT_ENUM)
#undef ESKIN_EXIT_ENUM
};

constexpr int exit_code(Exit e) { return static_cast<int>(e); }

}  // namespace eskin
