#pragma once
// CSV text as spreadsheets and GIS tools write it, split into cells a line (or a record) at a time:
// the one tokenizer of every swath CSV reader (areas, trigger data, the batch before's batch.csv).
//
// Dialects: cells may be quoted (RFC 4180, "" inside quotes is a quote, a quoted cell may hold
// the separator or '#'); the separator is ',', or ';' or a tab when the first line holding values
// has no comma (a line of numbers with decimal commas between semicolons, "12,5;55,1", is ';'
// too); lines end in LF, CRLF or a lone CR (old Mac); a UTF-8 BOM is skipped. '#' outside quotes
// starts a comment to the end of the line: a whole line ("# corners") or after the values
// ("12.5,55.1 # corner"); blank lines and lines of only a comment hold no values.
//
// Records::quoted_breaks reads CSV that swath wrote (batch.csv) as RFC 4180 has it: a quoted cell
// may hold line breaks, so a record ends at a line break outside quotes, and '#' is text anywhere
// (an area's name may hold one). The readers of the user's areas and trigger data keep lines.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace swath::base {

class CsvText {
 public:
  /// Where a record ends: `lines`, at every line break, '#' outside quotes starting a comment;
  /// `quoted_breaks`, at a line break outside quotes, no comments.
  enum class Records { lines, quoted_breaks };

  /// `text` is kept by reference and must outlive the reader; `source` names it in messages.
  CsvText(std::string_view text, std::string source, Records records = Records::lines);

  /// Moves to the next record holding values and splits it into cells, each trimmed of spaces and
  /// tabs; false at the end of the text. Throws InputError ("SOURCE: line N: column K opens a
  /// quote that the line does not close", "... has text after its closing quote"; with
  /// quoted_breaks "... that the text does not close").
  bool next();
  /// The cells of the current record.
  const std::vector<std::string>& cells() const { return cells_; }
  /// The number of the current record's first line, 1-based (every LF, CRLF or lone CR ends one
  /// line, inside quotes too).
  int line() const { return line_; }
  /// The separator, from the first line holding values: ',', ';' or '\t' (',' before that line).
  char separator() const { return separator_; }
  /// A cell's number (std::from_chars, no locale, an optional leading '+'). With ';' as the
  /// separator a decimal comma ("12,5", as spreadsheets write it in much of Europe) reads as a
  /// decimal point: a comma cannot separate columns there, so "12,5" has no other reading. Only
  /// in a cell with no '.': a thousands separator ("1.234,5") stays no number, not guessed at.
  std::optional<double> number(std::string_view cell) const { return number(cell, separator_); }
  static std::optional<double> number(std::string_view cell, char separator);

 private:
  std::size_t record_end() const;
  bool comments() const { return records_ == Records::lines; }
  bool ends_cell(char c) const { return c == separator_ || (comments() && c == '#'); }
  void split(std::string_view record);

  std::string_view text_;
  std::string source_;
  Records records_;
  std::size_t pos_ = 0;
  int line_ = 0;
  int lines_ended_ = 0;  // the line breaks before pos_
  bool detected_ = false;
  char separator_ = ',';
  std::vector<std::string> cells_;
};

/// "comma-separated", "semicolon-separated" or "tab-separated", for messages.
std::string separated_text(char separator);

/// The fields of `line` between runs of white space (space, \t, \n, \v, \f, \r): what reading
/// std::string after std::string from a stream in the C locale gives, without a stream (WPL rows).
/// The views point into `line`.
std::vector<std::string_view> whitespace_fields(std::string_view line);

/// The next line of `text` from `at` on, as std::getline gives it from a stream of `text` (without
/// its '\n'; none after a last '\n'), but a view into `text` rather than a copy; `at` moves past
/// it. False when no line is left.
bool next_line(std::string_view text, std::size_t& at, std::string_view& line);

}  // namespace swath::base
