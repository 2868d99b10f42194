// Every command example in README.md and docs/*.md is run and its output compared with the text
// the page shows (docs/reliability.md, "Documentation examples", says how a page writes one).
//
// An example is a fenced block whose first line starts with "$ ": each "$ " line (continued on
// the next line while it ends in a backslash) is run by /bin/sh from a scratch directory that
// links the source tree's share/, plans/ and tests/, with the built programs first on PATH; what it
// prints on stdout and stderr together must equal the lines shown below it, up to the next "$ "
// line (a blank line just before that one only separates the two). `$?` is the previous
// command's exit status, so "$ echo $?" shows it. A page runs its examples in order in one
// directory: a later example may read what an earlier one wrote.
//
// A block after "<!-- not run: WHY -->" is not run; after "<!-- not run under sanitizers: WHY -->"
// it is not run in the sanitizer build.
//
// With SWATH_UPDATE_DOC_EXAMPLES=1 the pages are rewritten with the outputs the programs print
// (scripts/update-doc-examples), as is docs/architecture.md's list of link dependencies.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace {

namespace fs = std::filesystem;

#ifdef SWATH_SANITIZED
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

bool updating() {
  const char* value = std::getenv("SWATH_UPDATE_DOC_EXAMPLES");
  return value != nullptr && std::string(value) == "1";
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines, std::size_t begin, std::size_t end) {
  std::string text;
  for (std::size_t i = begin; i < end; ++i) text += lines[i] + "\n";
  return text;
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

/// One "$ " command of an example and the output shown for it.
struct Step {
  std::string command;     // without "$ ", continuation lines joined by "\n"
  std::string shown;       // the lines shown below it, each ending in "\n"
  std::size_t line = 0;    // 1-based line of its "$ " in the page
  bool separated = false;  // a blank line follows the output, before the next "$ "
};

/// A fenced block of commands: its content lines [first, last) in the page.
struct Example {
  std::size_t first = 0;
  std::size_t last = 0;
  std::vector<std::string> command_lines;  // per step, its "$ " line and continuations as shown
  std::vector<Step> steps;
  std::string skipped;  // why it is not run here; empty: run
};

std::vector<Example> examples_of(const std::vector<std::string>& lines) {
  std::vector<Example> examples;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!starts_with(lines[i], "```")) continue;
    std::size_t end = i + 1;
    while (end < lines.size() && !starts_with(lines[end], "```")) ++end;
    const std::size_t open = i;
    i = end;
    if (open + 1 >= end || !starts_with(lines[open + 1], "$ ")) continue;
    Example example;
    example.first = open + 1;
    example.last = end;
    std::size_t before = open;
    while (before > 0 && lines[before - 1].empty()) --before;
    if (before > 0) {
      const std::string& note = lines[before - 1];
      if (starts_with(note, "<!-- not run:")) {
        example.skipped = note;
      } else if (starts_with(note, "<!-- not run under sanitizers:") && kSanitized) {
        example.skipped = note;
      }
    }
    for (std::size_t k = example.first; k < example.last;) {
      Step step;
      step.line = k + 1;
      std::string shown_command = lines[k];
      step.command = lines[k].substr(2);
      while (!lines[k].empty() && lines[k].back() == '\\' && k + 1 < example.last) {
        ++k;
        step.command += "\n" + lines[k];
        shown_command += "\n" + lines[k];
      }
      ++k;
      std::size_t out_end = k;
      while (out_end < example.last && !starts_with(lines[out_end], "$ ")) ++out_end;
      std::size_t shown_end = out_end;
      if (out_end < example.last && shown_end > k && lines[shown_end - 1].empty()) {
        step.separated = true;
        --shown_end;
      }
      step.shown = join_lines(lines, k, shown_end);
      example.command_lines.push_back(shown_command);
      example.steps.push_back(step);
      k = out_end;
    }
    examples.push_back(example);
  }
  return examples;
}

/// The source tree's folders an example reads from: linked into its scratch directory. Only
/// these, so that an example's output directory (`-o fleet`) never lands in the source tree.
const char* const kDataFolders[] = {"share", "plans", "tests"};

/// A scratch directory for a page's examples, with links to the data folders.
fs::path scratch_for(const std::string& page) {
  std::string name = page;
  std::replace(name.begin(), name.end(), '/', '-');
  const fs::path dir =
      fs::temp_directory_path() / ("swath-doc-examples-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* folder : kDataFolders) {
    fs::create_symlink(fs::path(SWATH_SOURCE_DIR) / folder, dir / folder);
  }
  return dir;
}

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs one command as the page shows it; returns what it printed (stdout and stderr) and sets
/// status to its exit status.
std::string run_step(const fs::path& dir, const std::string& command, int& status) {
  const fs::path script = dir / ".doc-example.sh";
  write_text(script, "cd " + quoted(dir.string()) + " || exit 125\nPATH=" +
                         quoted(SWATH_PROGRAM_DIR) + ":\"$PATH\"\nexport PATH\n(exit " +
                         std::to_string(status) + ")\n" + command + "\n");
  const std::string shell = "/bin/sh " + quoted(script.string()) + " 2>&1 </dev/null";
  FILE* pipe = ::popen(shell.c_str(), "r");
  std::string out;
  if (pipe == nullptr) {
    status = -1;
    return out;
  }
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  const int wait_status = ::pclose(pipe);
  status = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : 128;
  if (!out.empty() && out.back() != '\n') out += '\n';
  return out;
}

std::vector<std::string> pages() {
  std::vector<std::string> names{"README.md"};
  std::vector<std::string> docs;
  for (const auto& entry : fs::directory_iterator(fs::path(SWATH_SOURCE_DIR) / "docs")) {
    if (entry.path().extension() == ".md") {
      docs.push_back("docs/" + entry.path().filename().string());
    }
  }
  std::sort(docs.begin(), docs.end());
  names.insert(names.end(), docs.begin(), docs.end());
  return names;
}

class DocExamples : public testing::TestWithParam<std::string> {};

TEST_P(DocExamples, PrintWhatThePageShows) {
  const std::string page = GetParam();
  const fs::path path = fs::path(SWATH_SOURCE_DIR) / page;
  const std::string text = slurp(path);
  std::vector<std::string> lines = split_lines(text);
  std::vector<Example> examples = examples_of(lines);
  const fs::path dir = scratch_for(page);
  int status = 0;
  int run = 0;
  for (Example& example : examples) {
    if (!example.skipped.empty()) continue;
    for (std::size_t s = 0; s < example.steps.size(); ++s) {
      Step& step = example.steps[s];
      const std::string printed = run_step(dir, step.command, status);
      ++run;
      if (updating()) {
        // A command shown without output gets a blank line after the output it now shows.
        if (step.shown.empty() && !printed.empty() && s + 1 < example.steps.size()) {
          step.separated = true;
        }
        step.shown = printed;
      } else {
        EXPECT_EQ(printed, step.shown)
            << page << ":" << step.line << ": $ " << step.command
            << "\n(scripts/update-doc-examples rewrites the page with what the programs print)";
      }
    }
  }
  std::cout << page << ": " << run << " commands run\n";
  // Kept after a failure, to look at what the commands wrote.
  if (!HasFailure()) {
    fs::remove_all(dir);
    std::error_code not_empty;  // the other pages' directories may still be there
    fs::remove(dir.parent_path(), not_empty);
  }
  if (!updating()) return;
  // Rewrite the examples from the last one up, so that earlier line numbers stay valid.
  for (auto e = examples.rbegin(); e != examples.rend(); ++e) {
    std::vector<std::string> content;
    for (std::size_t s = 0; s < e->steps.size(); ++s) {
      for (const std::string& line : split_lines(e->command_lines[s] + "\n")) {
        content.push_back(line);
      }
      for (const std::string& line : split_lines(e->steps[s].shown)) content.push_back(line);
      if (e->steps[s].separated) content.push_back("");
    }
    lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(e->first),
                lines.begin() + static_cast<std::ptrdiff_t>(e->last));
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(e->first), content.begin(),
                 content.end());
  }
  const std::string rewritten = join_lines(lines, 0, lines.size());
  if (rewritten != text) {
    write_text(path, rewritten);
    std::cout << "rewrote " << page << "\n";
  }
}

INSTANTIATE_TEST_SUITE_P(Pages, DocExamples, testing::ValuesIn(pages()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

// docs/architecture.md lists each target's link dependencies between two markers; CMake writes
// the same list from the targets themselves (docs/CMakeLists.txt) at every configure.
TEST(ArchitecturePage, ListsTheLinkDependenciesCMakeHas) {
  const fs::path page = fs::path(SWATH_SOURCE_DIR) / "docs" / "architecture.md";
  const std::string text = slurp(page);
  const std::string begin_marker = "<!-- link dependencies: begin";
  const std::string end_marker = "<!-- link dependencies: end -->";
  const std::size_t begin = text.find(begin_marker);
  const std::size_t end = text.find(end_marker);
  ASSERT_NE(begin, std::string::npos) << "docs/architecture.md lacks " << begin_marker;
  ASSERT_NE(end, std::string::npos) << "docs/architecture.md lacks " << end_marker;
  const std::size_t list_begin = text.find('\n', begin) + 1;
  std::string shown = text.substr(list_begin, end - list_begin);
  const std::string generated = slurp(SWATH_LINK_DEPENDENCIES);
  ASSERT_FALSE(generated.empty()) << SWATH_LINK_DEPENDENCIES << " is missing";
  if (updating()) {
    if (shown != generated) {
      write_text(page, text.substr(0, list_begin) + generated + text.substr(end));
      std::cout << "rewrote docs/architecture.md\n";
    }
    return;
  }
#ifndef SWATH_FLEET_PYTHON
  // The page shows the default build, whose swath-fleet embeds Python (python/, docs/install.md);
  // this build has no Python (the sanitizer build, or no python3-dev): that link is left out.
  for (std::size_t at; (at = shown.find(", pybind11::embed")) != std::string::npos;)
    shown.erase(at, std::string(", pybind11::embed").size());
#endif
  EXPECT_EQ(shown, generated) << "docs/architecture.md's link dependencies are stale: "
                                 "scripts/update-doc-examples rewrites them";
}

}  // namespace
