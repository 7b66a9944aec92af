#pragma once
// Running the `vesselmesh` command from a test, as a user runs it.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace vesselmesh::test {

struct CliRun {
  int status;
  std::string output;  // stdout and stderr together
};

/// `vesselmesh ARGS` with its exit status (-1 when it did not exit normally: a crash) and its output.
inline CliRun run_cli(const std::string& args) {
  const std::string command = std::string(VESSELMESH_CLI) + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  CliRun run{-1, ""};
  if (!pipe) return run;
  std::array<char, 4096> buffer;
  while (std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) run.output.append(buffer.data(), n);
  const int raw = pclose(pipe);
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return run;
}

}  // namespace vesselmesh::test
