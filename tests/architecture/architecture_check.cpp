// The architecture's rules (docs/architecture.md, "Rules"), checked over the sources as text:
//  - MAVLink command numbers are named once, in mavlink/include/swath/mavlink/commands.hpp: no
//    MAV_CMD value typed by hand as a command outside mavlink/ (and tests/, whose hand-typed
//    numbers are the independent truth the writers are checked against);
//  - the fleet file is read in one place, vehicle/src/fleet_file.cpp: no other source (tests/
//    aside, which write fleet files) names two or more of its drones' keys as string literals;
//  - the state of charge is integrated in one place, vehicle/src/battery.cpp: no other source
//    (tests/ aside) turns a charge into a share of the capacity (3600 x capacity_ah);
//  - planning is the programs' (apps/, python/, bench/, fuzz/, tests/): no library folder links
//    swath::planning in its CMakeLists.txt or includes a swath/planning/ header (control reads
//    mission files through swath::missions, as energy and preflight do);
//  - no source file over --max-file-lines lines (1,000);
//  - no function body over --max-function-lines lines (150), found by matching braces at
//    namespace and class scope.
// Usage: swath_architecture_check [--max-file-lines N] [--max-function-lines N]
//                                 [--commands FILE] ROOT [DIR...]
// Scans ROOT/DIR (default: every source folder of the project); prints one line per violation
// (file:line: problem) and exits 1 when there is any, 2 on bad arguments.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Options {
  fs::path root;
  std::vector<std::string> dirs;
  fs::path commands;  // the header naming the MAV_CMD values
  std::size_t max_file_lines = 1000;
  std::size_t max_function_lines = 150;
};

struct Source {
  std::string name;      // as printed: relative to the root
  std::string raw;       // the file as written
  std::string no_notes;  // comments blanked (newlines kept)
  std::string code;      // comments, string and character literals and preprocessor lines blanked
  bool commands_checked = false;
};

struct Violation {
  std::string file;
  std::size_t line = 0;  // 0: the whole file
  std::string problem;
  std::string how;  // how it was found; not compared: two rules finding one number say it once
  bool operator<(const Violation& o) const {
    return std::tie(file, line, problem) < std::tie(o.file, o.line, o.problem);
  }
};

std::set<Violation> violations;  // in file and line order; one line found twice is said once

void report(const Source& s, std::size_t offset, const std::string& problem,
            const std::string& how = "") {
  const auto line = 1 + std::count(s.raw.begin(), s.raw.begin() + offset, '\n');
  violations.insert({s.name, static_cast<std::size_t>(line), problem, how});
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void blank(std::string& s, std::size_t from, std::size_t to) {
  for (std::size_t i = from; i < to && i < s.size(); ++i)
    if (s[i] != '\n') s[i] = ' ';
}

// Blanks comments in `no_notes`; in `code` also the contents of string and character literals
// (raw strings included) and preprocessor lines, so that braces and numbers in them are not read
// as code.
void strip(Source& s) {
  s.no_notes = s.raw;
  s.code = s.raw;
  const std::string& t = s.raw;
  std::size_t i = 0;
  bool line_start = true;
  while (i < t.size()) {
    const char c = t[i];
    if (line_start && c == '#') {  // a preprocessor line, with its continuations
      std::size_t end = i;
      while (end < t.size() && !(t[end] == '\n' && t[end - 1] != '\\')) ++end;
      blank(s.code, i, end);
      i = end;
      continue;
    }
    if (c == '\n')
      line_start = true;
    else if (!std::isspace(static_cast<unsigned char>(c)))
      line_start = false;
    if (c == '/' && i + 1 < t.size() && t[i + 1] == '/') {
      const std::size_t end = t.find('\n', i);
      const std::size_t stop = end == std::string::npos ? t.size() : end;
      blank(s.no_notes, i, stop);
      blank(s.code, i, stop);
      i = stop;
    } else if (c == '/' && i + 1 < t.size() && t[i + 1] == '*') {
      const std::size_t end = t.find("*/", i + 2);
      const std::size_t stop = end == std::string::npos ? t.size() : end + 2;
      blank(s.no_notes, i, stop);
      blank(s.code, i, stop);
      i = stop;
    } else if (c == 'R' && i + 1 < t.size() && t[i + 1] == '"' &&
               (i == 0 ||
                !(std::isalnum(static_cast<unsigned char>(t[i - 1])) || t[i - 1] == '_'))) {
      const std::size_t open = t.find('(', i + 2);
      const std::string close = ")" + t.substr(i + 2, open - i - 2) + "\"";
      const std::size_t end = t.find(close, open);
      const std::size_t stop = end == std::string::npos ? t.size() : end + close.size();
      blank(s.code, i + 2, stop - 1);
      i = stop;
    } else if (c == '"' ||
               (c == '\'' &&
                !(i > 0 && std::isxdigit(static_cast<unsigned char>(t[i - 1])))) /* 1'000 */) {
      std::size_t j = i + 1;
      while (j < t.size() && t[j] != c && t[j] != '\n') j += t[j] == '\\' ? 2 : 1;
      blank(s.code, i + 1, j);
      i = j + 1;
    } else {
      ++i;
    }
  }
}

// The MAV_CMD values: those commands.hpp names, and a few more swath does not send (so that a
// hand-typed one is caught before it is named).
std::set<long> command_values(const fs::path& header) {
  std::set<long> values{17, 18, 31, 84, 85, 177, 183, 530, 2500};
  const std::string text = read_file(header);
  const std::size_t from = text.find("enum class Cmd");
  const std::size_t to = text.find("};", from);
  if (from == std::string::npos || to == std::string::npos) {
    std::cerr << header.string() << ": no `enum class Cmd` found\n";
    std::exit(2);
  }
  const std::string body = text.substr(from, to - from);
  const std::regex value(R"(=\s*(\d+))");
  for (auto m = std::sregex_iterator(body.begin(), body.end(), value); m != std::sregex_iterator();
       ++m)
    values.insert(std::stol((*m)[1]));
  return values;
}

bool is_command(const std::string& number, const std::set<long>& commands) {
  return commands.count(std::stol(number)) > 0;
}

void check_pattern(const Source& s, const std::string& text, const std::regex& pattern,
                   const std::set<long>& commands, const std::string& what) {
  for (auto m = std::sregex_iterator(text.begin(), text.end(), pattern);
       m != std::sregex_iterator(); ++m)
    if (is_command((*m)[1], commands))
      report(s, static_cast<std::size_t>(m->position(1)),
             "MAV_CMD " + (*m)[1].str() + " typed by hand", what);
}

std::size_t matching_brace(const std::string& code, std::size_t open) {
  int depth = 0;
  for (std::size_t i = open; i < code.size(); ++i) {
    if (code[i] == '{') ++depth;
    if (code[i] == '}' && --depth == 0) return i;
  }
  return code.size();
}

// `case N:` in a switch on a command.
void check_switches(const Source& s, const std::set<long>& commands) {
  static const std::regex switch_on(R"(\bswitch\s*\(([^{]*)\)\s*\{)");
  static const std::regex command_name(R"(cmd|command)", std::regex::icase);
  static const std::regex case_label(R"(\bcase\s+(\d+)\s*:)");
  for (auto m = std::sregex_iterator(s.code.begin(), s.code.end(), switch_on);
       m != std::sregex_iterator(); ++m) {
    if (!std::regex_search((*m)[1].str(), command_name)) continue;
    const std::size_t open = m->position(0) + m->length(0) - 1;
    const std::size_t close = matching_brace(s.code, open);
    const std::string body = s.code.substr(open, close - open);
    for (auto c = std::sregex_iterator(body.begin(), body.end(), case_label);
         c != std::sregex_iterator(); ++c)
      if (is_command((*c)[1], commands))
        report(s, open + c->position(1), "MAV_CMD " + (*c)[1].str() + " typed by hand",
               "a case of a switch on a command");
  }
}

void check_commands(const Source& s, const std::set<long>& commands) {
  // A command compared with or assigned a number: `cmd == 16`, `item.command = 22`, `16 != cmd`.
  static const std::regex assigned(
      R"(\b\w*(?:cmd|command)\w*(?:\[\w*\])?\s*(?:==|!=|=|\+=)\s*\(?\s*(\d+)\b)",
      std::regex::icase);
  static const std::regex compared(R"(\b(\d+)\s*(?:==|!=)\s*[\w.>-]*(?:cmd|command))",
                                   std::regex::icase);
  // A command in JSON: "command": 16 in text, {"command", 16}, j["command"] = 16.
  static const std::regex json(R"re("command"\s*\]?\s*[:,=]\s*(\d+)\b)re");
  // Arguments that are commands: a WPL row's fourth, and the fence and rally commands anywhere.
  static const std::regex wpl_row(R"(\bwpl_row\s*\([^,;]*,[^,;]*,[^,;]*,\s*(\d+)\b)");
  static const std::regex fence_rally(R"(\b(500[1-4]|5100)\b)");
  check_pattern(s, s.code, assigned, commands, "a command assigned or compared");
  check_pattern(s, s.code, compared, commands, "a command compared");
  check_pattern(s, s.no_notes, json, commands, "a JSON \"command\"");
  check_pattern(s, s.code, wpl_row, commands, "a WPL row's command");
  check_pattern(s, s.code, fence_rally, commands, "a fence or rally command");
  check_switches(s, commands);
}

// The keys only a fleet file's drones have (docs/formats.md). One of them may name a value in a
// JSON summary; two or more in one file are a reader of the fleet file (or a writer of it, which
// belongs beside the reader).
void check_fleet_file_readers(const Source& s) {
  static const std::regex key(
      R"re("(battery_level|endurance_s|max_flight_time_s|approach_speed_m_s|approach_within_m|)re"
      R"re(accel_m_s2|recharge_s|home_m)")re");
  std::set<std::string> keys;
  std::size_t first = std::string::npos;
  for (auto m = std::sregex_iterator(s.no_notes.begin(), s.no_notes.end(), key);
       m != std::sregex_iterator(); ++m) {
    keys.insert((*m)[1].str());
    first = std::min(first, static_cast<std::size_t>(m->position(0)));
  }
  if (keys.size() < 2) return;
  std::string named;
  for (const std::string& k : keys) named += (named.empty() ? "" : ", ") + k;
  report(s, first, "a second fleet-file reader (" + named + ")");
}

// A charge turned into a share of the capacity, q / (3600 Q_c): a state-of-charge integrator.
void check_soc_integrators(const Source& s) {
  static const std::regex share(
      R"(\b3600(?:\.0*)?\s*\*\s*[\w.\[\]>-]*capacity_ah\b|\bcapacity_ah\s*\*\s*3600\b)");
  for (auto m = std::sregex_iterator(s.code.begin(), s.code.end(), share);
       m != std::sregex_iterator(); ++m)
    report(s, static_cast<std::size_t>(m->position(0)), "a second state-of-charge integrator");
}

// The library folders that sit below or beside planning (docs/architecture.md, "Libraries and
// their floors"): none of them may use it.
bool below_planning(const std::string& relative) {
  static const std::vector<std::string> folders{"base/",    "geometry/", "vehicle/", "missions/",
                                                "render/",  "web/",      "energy/",  "preflight/",
                                                "control/", "fleet/",    "worlds/",  "mavlink/"};
  return std::any_of(folders.begin(), folders.end(),
                     [&](const std::string& f) { return relative.rfind(f, 0) == 0; });
}

std::string folder_of(const std::string& relative) {
  return relative.substr(0, relative.find('/'));
}

// `#include "swath/planning/..."` in a library below planning.
void check_planning_includes(const Source& s) {
  static const std::regex include(R"(#\s*include\s*[<"]swath/planning/)");
  std::smatch m;
  if (std::regex_search(s.no_notes, m, include))
    report(s, static_cast<std::size_t>(m.position(0)),
           folder_of(s.name) + " uses planning (a swath/planning/ header)");
}

// `swath::planning` or `swath_planning` named in a CMakeLists.txt of a library below planning.
void check_planning_links(const fs::path& path, const std::string& relative) {
  Source s;
  s.name = relative;
  s.raw = read_file(path);
  s.no_notes = s.raw;
  for (std::size_t at = s.no_notes.find('#'); at != std::string::npos;
       at = s.no_notes.find('#', at + 1))  // CMake comments (a `#` in a string is not one here)
    blank(s.no_notes, at, s.no_notes.find('\n', at));
  static const std::regex link(R"(\bswath(?:::|_)planning\b)");
  std::smatch m;
  if (std::regex_search(s.no_notes, m, link))
    report(s, static_cast<std::size_t>(m.position(0)),
           folder_of(relative) + " links planning (" + m.str() + ")");
}

// A `{` at namespace or class scope opens a function body when what precedes it (since the last
// `;`, `{` or `}`) has a parameter list and is not an initializer or a class.
enum class Scope { transparent, function, other, init };

Scope scope_of(const std::string& header) {
  static const std::regex type_or_namespace(
      R"(^\s*(?:template\s*<[^{]*>\s*)?(?:class|struct|union|enum|namespace|extern)\b)");
  static const std::regex named_namespace(R"(^\s*(?:inline\s+)?namespace\b)");
  if (std::regex_search(header, type_or_namespace) || std::regex_search(header, named_namespace))
    return Scope::transparent;
  const std::size_t paren = header.find('(');
  if (paren == std::string::npos) return Scope::other;
  std::string before = header.substr(0, paren);
  before = std::regex_replace(before, std::regex(R"(operator\s*\S+)"), "operator");
  if (before.find('=') != std::string::npos) return Scope::other;  // an initializer or lambda
  return Scope::function;
}

std::string function_name(const std::string& header) {
  static const std::regex name(R"(([\w:~]+(?:\s*operator\s*[^\s(]+)?)\s*\()");
  std::smatch m;
  return std::regex_search(header, m, name) ? m[1].str() : std::string("?");
}

// A function that names a command (`int mav_command(...)`) returning numbers: `return 16;`.
void check_returned_commands(const Source& s, std::size_t open, std::size_t close,
                             const std::set<long>& commands) {
  static const std::regex returned(R"(\breturn\b[^;]*;)");
  static const std::regex number(R"(\b(\d+)\b)");
  const std::string body = s.code.substr(open, close - open);
  for (auto r = std::sregex_iterator(body.begin(), body.end(), returned);
       r != std::sregex_iterator(); ++r) {
    const std::string statement = r->str();
    for (auto n = std::sregex_iterator(statement.begin(), statement.end(), number);
         n != std::sregex_iterator(); ++n)
      if (is_command((*n)[1], commands))
        report(s, open + r->position(0) + n->position(1),
               "MAV_CMD " + (*n)[1].str() + " typed by hand",
               "returned by a function that names a command");
  }
}

// Finds the function bodies; reports the long ones, and hand-typed commands returned by those
// that name a command when `commands` is given.
void check_functions(const Source& s, std::size_t max_lines, const std::set<long>* commands) {
  static const std::regex member_init_list(R"(\)\s*:[^:])");
  // mav_command, command_of, cmd_for: a function that gives a command (not `commands_sent`).
  static const std::regex command_name(R"((?:cmd|command)(?:_of|_for)?$)", std::regex::icase);
  const std::string& code = s.code;
  struct Open {
    Scope scope;
    std::size_t at;
    std::string name;
  };
  std::vector<Open> stack;
  std::size_t header_start = 0;
  auto line_of = [&](std::size_t at) {
    return static_cast<std::size_t>(std::count(code.begin(), code.begin() + at, '\n')) + 1;
  };
  for (std::size_t i = 0; i < code.size(); ++i) {
    const char c = code[i];
    const bool at_scope = stack.empty() || stack.back().scope == Scope::transparent;
    if (c == '{') {
      if (!at_scope) {
        stack.push_back({Scope::other, i, {}});
        continue;
      }
      const std::string header = code.substr(header_start, i - header_start);
      // A member initialized with braces in a constructor's initializer list: `: x_{a} {`.
      std::size_t k = i;
      while (k > header_start && std::isspace(static_cast<unsigned char>(code[k - 1]))) --k;
      const bool member_init =
          k > header_start &&
          (std::isalnum(static_cast<unsigned char>(code[k - 1])) || code[k - 1] == '_') &&
          std::regex_search(header, member_init_list);
      const Scope scope = member_init ? Scope::init : scope_of(header);
      stack.push_back({scope, i, scope == Scope::function ? function_name(header) : ""});
      if (scope != Scope::init) header_start = i + 1;
    } else if (c == '}' && !stack.empty()) {
      const Open open = stack.back();
      stack.pop_back();
      if (open.scope == Scope::function) {
        const std::size_t lines = line_of(i) - line_of(open.at) + 1;
        if (lines > max_lines)
          report(s, open.at,
                 "function " + open.name + " is " + std::to_string(lines) + " lines (limit " +
                     std::to_string(max_lines) + "); split it into named steps");
        if (commands && std::regex_search(open.name, command_name))
          check_returned_commands(s, open.at, i, *commands);
      }
      if (open.scope != Scope::init && (stack.empty() || stack.back().scope == Scope::transparent))
        header_start = i + 1;
    } else if (c == ';' && at_scope) {
      header_start = i + 1;
    }
  }
}

// A "§" followed by a digit in a comment, on a line that names no paper ("paper 00N"): a section
// of a document outside the repository. C++ comments are found by `no_notes`; in the other
// files (CMake, Python, shell) every line is read, as their § marks are in `#` comments.
void check_section_marks(const Source& s, bool cpp) {
  static const std::string mark = "\xC2\xA7";  // § in UTF-8
  static const std::regex paper(R"(\bpaper 0\d\d\b)", std::regex::icase);
  for (std::size_t at = s.raw.find(mark); at != std::string::npos;
       at = s.raw.find(mark, at + mark.size())) {
    const std::size_t after = at + mark.size();
    if (after >= s.raw.size() || !std::isdigit(static_cast<unsigned char>(s.raw[after]))) continue;
    if (cpp && s.no_notes[at] != ' ') continue;  // in code or a string, not a comment
    const std::size_t begin =
        s.raw.rfind('\n', at) == std::string::npos ? 0 : s.raw.rfind('\n', at) + 1;
    const std::size_t end = std::min(s.raw.find('\n', at), s.raw.size());
    if (std::regex_search(s.raw.begin() + static_cast<std::ptrdiff_t>(begin),
                          s.raw.begin() + static_cast<std::ptrdiff_t>(end), paper))
      continue;
    std::size_t stop = after;
    while (stop < s.raw.size() &&
           (std::isalnum(static_cast<unsigned char>(s.raw[stop])) || s.raw[stop] == '.'))
      ++stop;
    while (s.raw[stop - 1] == '.') --stop;  // a sentence's full stop
    report(s, at, "section mark " + s.raw.substr(at, stop - at) + " names no paper");
  }
}

bool is_script(const fs::path& p, const std::string& relative) {
  const std::string ext = p.extension().string();
  return p.filename() == "CMakeLists.txt" || ext == ".cmake" || ext == ".py" || ext == ".sh" ||
         relative.rfind("scripts/", 0) == 0;
}

bool is_source(const fs::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".cpp" || ext == ".hpp" || ext == ".h" || ext == ".cc";
}

// Folders whose command numbers are the vocabulary itself (mavlink/) or independent truth
// (tests/); the planted examples are checked only when named on the command line.
bool commands_exempt(const std::string& relative) {
  return relative.rfind("mavlink/", 0) == 0 || relative.rfind("tests/", 0) == 0;
}

// The one state-of-charge integrator, and the tests' independent truth.
bool soc_exempt(const std::string& relative) {
  return relative == "vehicle/src/battery.cpp" || relative.rfind("tests/", 0) == 0;
}

// The fleet file's one reader, and the tests, which write fleet files as text.
bool fleet_keys_exempt(const std::string& relative) {
  return relative == "vehicle/src/fleet_file.cpp" || relative.rfind("tests/", 0) == 0;
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << a << ": expected a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--max-file-lines")
      o.max_file_lines = std::stoul(value());
    else if (a == "--max-function-lines")
      o.max_function_lines = std::stoul(value());
    else if (a == "--commands")
      o.commands = value();
    else
      positional.push_back(a);
  }
  if (positional.empty()) {
    std::cerr << "usage: swath_architecture_check [--max-file-lines N] [--max-function-lines N] "
                 "[--commands FILE] ROOT [DIR...]\n";
    std::exit(2);
  }
  o.root = positional.front();
  o.dirs.assign(positional.begin() + 1, positional.end());
  if (o.dirs.empty())
    o.dirs = {"base",      "geometry", "vehicle", "mavlink", "missions", "planning",
              "preflight", "energy",   "control", "fleet",   "worlds",   "render",
              "web",       "apps",     "bench",   "fuzz",    "tests",    "scripts"};
  if (o.commands.empty()) o.commands = o.root / "mavlink/include/swath/mavlink/commands.hpp";
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const std::set<long> commands = command_values(o.commands);
  std::vector<fs::path> files;
  std::vector<fs::path> cmake_files;  // checked for links only
  std::vector<fs::path> scripts;      // CMake, Python and shell: checked for section marks only
  for (const std::string& dir : o.dirs) {
    if (!fs::is_directory(o.root / dir)) {
      std::cerr << (o.root / dir).string() << ": not a folder\n";
      return 2;
    }
    for (const auto& e : fs::recursive_directory_iterator(o.root / dir)) {
      const std::string relative = fs::relative(e.path(), o.root).generic_string();
      // The planted violations are checked on their own (architecture/planted-* tests).
      if (relative.rfind("tests/architecture/planted", 0) == 0) continue;
      if (e.is_regular_file() && is_source(e.path())) files.push_back(e.path());
      if (e.is_regular_file() && is_script(e.path(), relative)) scripts.push_back(e.path());
      if (e.is_regular_file() && e.path().filename() == "CMakeLists.txt" &&
          below_planning(relative))
        cmake_files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& path : files) {
    Source s;
    s.name = fs::relative(path, o.root).generic_string();
    s.raw = read_file(path);
    strip(s);
    const auto lines = static_cast<std::size_t>(std::count(s.raw.begin(), s.raw.end(), '\n'));
    if (lines > o.max_file_lines)
      violations.insert({s.name, 0,
                         std::to_string(lines) + " lines (limit " +
                             std::to_string(o.max_file_lines) + "); split it by job",
                         ""});
    const bool check_commands_here = !commands_exempt(s.name);
    check_functions(s, o.max_function_lines, check_commands_here ? &commands : nullptr);
    if (check_commands_here) check_commands(s, commands);
    if (!fleet_keys_exempt(s.name)) check_fleet_file_readers(s);
    if (!soc_exempt(s.name)) check_soc_integrators(s);
    if (below_planning(s.name)) check_planning_includes(s);
    check_section_marks(s, true);
  }
  std::sort(scripts.begin(), scripts.end());
  for (const fs::path& path : scripts) {
    Source s;
    s.name = fs::relative(path, o.root).generic_string();
    s.raw = read_file(path);
    s.no_notes = s.raw;
    check_section_marks(s, false);
  }
  std::sort(cmake_files.begin(), cmake_files.end());
  for (const fs::path& path : cmake_files)
    check_planning_links(path, fs::relative(path, o.root).generic_string());
  for (const Violation& v : violations)
    std::cout << v.file << (v.line ? ":" + std::to_string(v.line) : std::string()) << ": "
              << v.problem << (v.how.empty() ? "" : " (" + v.how + ")") << "\n";
  if (std::any_of(violations.begin(), violations.end(),
                  [](const Violation& v) { return v.problem.rfind("MAV_CMD", 0) == 0; }))
    std::cout << "Name MAV_CMD values with swath::mavlink::Cmd "
                 "(mavlink/include/swath/mavlink/commands.hpp).\n";
  if (std::any_of(violations.begin(), violations.end(), [](const Violation& v) {
        return v.problem.rfind("a second fleet-file reader", 0) == 0;
      }))
    std::cout << "Read fleet files with swath::vehicle::parse_fleet_file "
                 "(vehicle/include/swath/vehicle/fleet_file.hpp).\n";
  if (std::any_of(violations.begin(), violations.end(), [](const Violation& v) {
        return v.problem == "a second state-of-charge integrator";
      }))
    std::cout << "Draw charge with swath::vehicle::soc_after_charge "
                 "(vehicle/include/swath/vehicle/battery.hpp).\n";
  if (std::any_of(violations.begin(), violations.end(), [](const Violation& v) {
        return v.problem.find(" planning (") != std::string::npos;
      }))
    std::cout << "Only the programs use swath::planning; read mission files with swath::missions "
                 "(missions/include/swath/missions/).\n";
  if (std::any_of(violations.begin(), violations.end(),
                  [](const Violation& v) { return v.problem.rfind("section mark", 0) == 0; }))
    std::cout << "Name the paper (\"paper 000 \u00A75.1\") or cite the docs page and heading "
                 "(\"docs/swath-control.md, 'The simulated multirotor'\").\n";
  std::cout << files.size() + scripts.size() << " files checked, " << violations.size()
            << " violation" << (violations.size() == 1 ? "" : "s") << "\n";
  return violations.empty() ? 0 : 1;
}
