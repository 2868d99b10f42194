#include "swath/base/csv_text.hpp"

#include <algorithm>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"

namespace swath::base {
namespace {

std::string_view trimmed(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// The line up to a '#' outside quotes (a quote opens or closes quoting wherever it stands: the
// separator is not known yet when this is first asked).
std::string_view before_comment(std::string_view line) {
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '"') quoted = !quoted;
    if (!quoted && line[i] == '#') return line.substr(0, i);
  }
  return line;
}

// The separator, from the first line holding values (its comment left off): a comma (outside
// quotes) if it has one, else ';' or a tab if it has one, else a comma (a single column). A line
// of numbers with decimal commas between semicolons ("12,5;55,1", no header) is ';' too.
char detect_separator(std::string_view line) {
  bool quoted = false, comma = false, semicolon = false, tab = false;
  for (const char c : line) {
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    comma |= c == ',';
    semicolon |= c == ';';
    tab |= c == '\t';
  }
  if (comma && semicolon) {
    bool numbers = true;
    for (std::size_t start = 0; numbers && start <= line.size();) {
      const auto end = std::min(line.find(';', start), line.size());
      numbers = CsvText::number(trimmed(line.substr(start, end - start)), ';').has_value();
      start = end + 1;
    }
    if (numbers) return ';';
  }
  return comma ? ',' : semicolon ? ';' : tab ? '\t' : ',';
}

}  // namespace

CsvText::CsvText(std::string_view text, std::string source)
    : text_(text), source_(std::move(source)) {
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 BOM
}

bool CsvText::next() {
  while (pos_ <= text_.size()) {
    // A line ends at LF, CRLF or a lone CR.
    auto eol = text_.find_first_of("\r\n", pos_);
    if (eol == std::string_view::npos) eol = text_.size();
    const std::string_view line = trimmed(text_.substr(pos_, eol - pos_));
    pos_ = eol + (text_.substr(eol, 2) == "\r\n" ? 2 : 1);
    ++line_;
    const std::string_view values = trimmed(before_comment(line));
    if (values.empty()) continue;
    if (!detected_) {
      separator_ = detect_separator(values);
      detected_ = true;
    }
    split(line);
    return true;
  }
  return false;
}

// The cells of a line split at the separator, each trimmed; a cell in double quotes may hold the
// separator or '#', and "" inside it is one quote. Text after a closing quote is refused; '#'
// outside quotes ends the line.
void CsvText::split(std::string_view line) {
  cells_.clear();
  const auto fail = [&](const std::string& problem) {
    throw InputError(source_ + ": line " + std::to_string(line_) + ": column " +
                     std::to_string(cells_.size() + 1) + " " + problem);
  };
  const auto blank = [&](std::size_t i) {
    return i < line.size() && line[i] != separator_ && (line[i] == ' ' || line[i] == '\t');
  };
  std::size_t i = 0;
  while (true) {
    while (blank(i)) ++i;
    if (i < line.size() && line[i] == '"') {
      std::string cell;
      for (++i;; ++i) {
        if (i >= line.size()) fail("opens a quote that the line does not close");
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            cell += '"';
            ++i;
            continue;
          }
          ++i;
          break;
        }
        cell += line[i];
      }
      while (blank(i)) ++i;
      if (i < line.size() && line[i] != separator_ && line[i] != '#')
        fail("has text after its closing quote");
      cells_.emplace_back(trimmed(cell));
    } else {
      auto end = line.find_first_of(separator_ == ',' ? ",#" : separator_ == ';' ? ";#" : "\t#", i);
      if (end == std::string_view::npos) end = line.size();
      cells_.emplace_back(trimmed(line.substr(i, end - i)));
      i = end;
    }
    if (i >= line.size() || line[i] == '#') break;
    ++i;  // the separator
  }
}

std::optional<double> CsvText::number(std::string_view cell, char separator) {
  std::string text(cell);
  if (separator == ';' && text.find('.') == std::string::npos)
    std::replace(text.begin(), text.end(), ',', '.');
  double value = 0;
  if (!parse_number(text, value)) return std::nullopt;
  return value;
}

std::string separated_text(char separator) {
  return separator == ';'    ? "semicolon-separated"
         : separator == '\t' ? "tab-separated"
                             : "comma-separated";
}

bool next_line(std::string_view text, std::size_t& at, std::string_view& line) {
  if (at >= text.size()) return false;
  const std::size_t end = std::min(text.find('\n', at), text.size());
  line = text.substr(at, end - at);
  at = end + 1;
  return true;
}

std::vector<std::string_view> whitespace_fields(std::string_view line) {
  // The C locale's isspace, without a call per character.
  const auto space = [](char c) { return c == ' ' || (c >= '\t' && c <= '\r'); };
  std::vector<std::string_view> fields;
  std::size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && space(line[k])) ++k;
    const std::size_t first = k;
    while (k < line.size() && !space(line[k])) ++k;
    if (k > first) fields.push_back(line.substr(first, k - first));
  }
  return fields;
}

}  // namespace swath::base
