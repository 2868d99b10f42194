// swath._swath: the `swath` program's classify and plan commands run in this process, with the
// same option parser, the same checks and the same files as the command line (docs/install.md).
// The Python package (python/swath/__init__.py) turns keyword arguments into that command line.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "classify_command.hpp"
#include "command.hpp"
#include "plan_command.hpp"

namespace py = pybind11;

namespace swath::python {
namespace {

// The commands the module runs, as swath's main.cpp registers them.
std::vector<std::unique_ptr<apps::Command>> commands() {
  std::vector<std::unique_ptr<apps::Command>> out;
  out.push_back(std::make_unique<apps::ClassifyCommand>());
  out.push_back(std::make_unique<apps::PlanCommand>());
  return out;
}

// What the program writes to one of the standard streams while it runs, taken from the file
// descriptor itself: the commands print through both printf and std::cout/std::cerr.
class Capture {
 public:
  explicit Capture(int fd) : fd_(fd), file_(std::tmpfile()) {
    if (file_ == nullptr) throw std::runtime_error("swath: cannot create a temporary file");
    flush();
    saved_ = ::dup(fd_);
    if (saved_ < 0 || ::dup2(::fileno(file_), fd_) < 0) {
      std::fclose(file_);
      throw std::runtime_error("swath: cannot redirect the standard streams");
    }
  }
  Capture(const Capture&) = delete;
  Capture& operator=(const Capture&) = delete;
  ~Capture() {
    if (saved_ >= 0) restore();
    std::fclose(file_);
  }

  /// Puts the stream back and returns what was written to it.
  std::string finish() {
    restore();
    std::string text;
    std::rewind(file_);
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, file_)) > 0;)
      text.append(buffer, n);
    return text;
  }

 private:
  static void flush() {
    std::cout.flush();
    std::cerr.flush();
    std::fflush(stdout);
    std::fflush(stderr);
  }
  void restore() {
    flush();
    ::dup2(saved_, fd_);
    ::close(saved_);
    saved_ = -1;
  }

  int fd_;
  std::FILE* file_;
  int saved_ = -1;
};

/// Runs `swath ARGS...` (ARGS[0] the command) and returns (exit code, stdout, stderr).
std::tuple<int, std::string, std::string> run(const std::vector<std::string>& args) {
  std::vector<std::string> words{"swath"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  auto registered = commands();
  Capture out(STDOUT_FILENO);
  Capture err(STDERR_FILENO);
  const int code = apps::run_program("swath", "swath: drone area survey planner", "", registered,
                                     static_cast<int>(words.size()), argv.data());
  std::string err_text = err.finish();
  std::string out_text = out.finish();
  return {code, std::move(out_text), std::move(err_text)};
}

/// The long options of `swath COMMAND`: (name without "--", takes a value, may repeat).
std::vector<std::tuple<std::string, bool, bool>> options(const std::string& command) {
  for (const auto& c : commands()) {
    if (command != c->name()) continue;
    CLI::App app;
    c->setup(app);
    std::vector<std::tuple<std::string, bool, bool>> out;
    for (const CLI::Option* option : app.get_options()) {
      for (const std::string& name : option->get_lnames())
        out.emplace_back(name, option->get_items_expected_max() != 0,
                         option->get_expected_max() > 1);
    }
    return out;
  }
  throw std::invalid_argument("swath has no command '" + command + "' in this module");
}

}  // namespace
}  // namespace swath::python

PYBIND11_MODULE(_swath, m) {
  m.doc() = "swath's commands run in this process (the swath package wraps them)";
  m.def("run", &swath::python::run, py::arg("args"),
        "Runs `swath ARGS...` in this process; returns (exit code, stdout, stderr)");
  m.def("options", &swath::python::options, py::arg("command"),
        "The long options of `swath COMMAND`: (name, takes a value, may repeat)");
  m.attr("version") = SWATH_VERSION;
}
