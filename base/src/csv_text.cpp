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

// How many lines `text` ends: every LF, CRLF or lone CR.
int line_breaks(std::string_view text) {
  int breaks = 0;
  for (std::size_t i = 0; i < text.size(); ++i)
    breaks += text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'));
  return breaks;
}

}  // namespace

CsvText::CsvText(std::string_view text, std::string source, Records records)
    : text_(text), source_(std::move(source)), records_(records) {
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 BOM
}

// Where the record from pos_ on ends: its first line break (LF, CRLF or a lone CR), outside
// quotes with quoted_breaks; the end of the text if none.
std::size_t CsvText::record_end() const {
  if (comments()) return std::min(text_.find_first_of("\r\n", pos_), text_.size());
  bool quoted = false;
  for (std::size_t i = pos_; i < text_.size(); ++i) {
    if (text_[i] == '"') quoted = !quoted;
    if (!quoted && (text_[i] == '\r' || text_[i] == '\n')) return i;
  }
  return text_.size();
}

bool CsvText::next() {
  while (pos_ <= text_.size()) {
    const std::size_t end = record_end();
    const std::string_view record = trimmed(text_.substr(pos_, end - pos_));
    line_ = lines_ended_ + 1;
    lines_ended_ += line_breaks(record) + 1;
    pos_ = end + (text_.substr(end, 2) == "\r\n" ? 2 : 1);
    const std::string_view values = comments() ? trimmed(before_comment(record)) : record;
    if (values.empty()) continue;
    if (!detected_) {
      separator_ = detect_separator(values);
      detected_ = true;
    }
    split(record);
    return true;
  }
  return false;
}

// The cells of a record split at the separator, each trimmed; a cell in double quotes may hold the
// separator or '#' (and line breaks with quoted_breaks), and "" inside it is one quote. Text after
// a closing quote is refused; with comments, '#' outside quotes ends the record.
void CsvText::split(std::string_view record) {
  cells_.clear();
  const auto fail = [&](const std::string& problem) {
    throw InputError(source_ + ": line " + std::to_string(line_) + ": column " +
                     std::to_string(cells_.size() + 1) + " " + problem);
  };
  const auto blank = [&](std::size_t i) {
    return i < record.size() && record[i] != separator_ && (record[i] == ' ' || record[i] == '\t');
  };
  std::size_t i = 0;
  while (true) {
    while (blank(i)) ++i;
    if (i < record.size() && record[i] == '"') {
      std::string cell;
      for (++i;; ++i) {
        if (i >= record.size())
          fail(comments() ? "opens a quote that the line does not close"
                          : "opens a quote that the text does not close");
        if (record[i] == '"') {
          if (i + 1 < record.size() && record[i + 1] == '"') {
            cell += '"';
            ++i;
            continue;
          }
          ++i;
          break;
        }
        cell += record[i];
      }
      while (blank(i)) ++i;
      if (i < record.size() && !ends_cell(record[i])) fail("has text after its closing quote");
      cells_.emplace_back(trimmed(cell));
    } else {
      const std::size_t start = i;
      while (i < record.size() && !ends_cell(record[i])) ++i;
      cells_.emplace_back(trimmed(record.substr(start, i - start)));
    }
    if (i >= record.size() || record[i] != separator_) break;  // the end, or a comment
    ++i;                                                       // the separator
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
