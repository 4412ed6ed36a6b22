#pragma once
// For command tests: parse `args` (without the program name) with an app that
// only has the subcommand `add` registers; return what it printed on stdout.
// Exceptions from the command's callback propagate to the test.
#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace dsswarm::test {

inline std::string run_cli(void (*add)(CLI::App&), const std::vector<std::string>& args) {
  CLI::App app("test");
  add(app);
  std::vector<const char*> argv = {"dsswarm"};
  for (const auto& a : args) argv.push_back(a.c_str());
  testing::internal::CaptureStdout();
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (...) {
    testing::internal::GetCapturedStdout();
    throw;
  }
  return testing::internal::GetCapturedStdout();
}

}  // namespace dsswarm::test
