#include "shell_text.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string_view>

#include "swath/base/input_error.hpp"

namespace swath::apps {

namespace {

// The word as a message may show it: control characters as '?', at most 60 bytes.
std::string shown(const std::string& word) {
  std::string out;
  for (const char c : word.substr(0, 60))
    out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? '?' : c;
  return word.size() > 60 ? out + "..." : out;
}

}  // namespace

std::string shell_word(const std::string& word) {
  // A line break ends a job line for GNU parallel, Slurm's array scripts and `while read`,
  // whatever the shell's quoting says; a tab or carriage return is split on by some of them. No
  // quoting a POSIX shell reads carries them on one line, so such a word is refused.
  const auto control = std::find_if(word.begin(), word.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
  });
  if (control != word.end())
    throw base::InputError("\"" + shown(word) +
                           "\" holds a line break or another control character, which no job "
                           "line can carry safely; rename it");
  const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) ||
           std::string_view("-_./,:=+@").find(c) != std::string_view::npos;
  });
  if (plain) return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string csv_field(const std::string& text) {
  // A spreadsheet runs a cell that starts with = + - @ (or a tab or CR before one) as a formula:
  // such text keeps a leading apostrophe, which spreadsheets show as text (OWASP's advice).
  const bool formula =
      !text.empty() && std::string_view("=+-@\t\r").find(text[0]) != std::string_view::npos;
  if (formula) return csv_field("'" + text);
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string own_program_path(const std::string& fallback) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? fallback : self.string();
}

}  // namespace swath::apps
