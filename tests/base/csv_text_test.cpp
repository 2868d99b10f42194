// base::CsvText, the tokenizer of every CSV reader: the dialects split to the same cells, '#'
// outside quotes ends a line (whole-line and trailing comments), inside quotes it is text, and
// malformed quoting is refused naming the line and the column.
#include "swath/base/csv_text.hpp"

#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "swath/base/input_error.hpp"

namespace swath::base {
namespace {

using Lines = std::vector<std::pair<int, std::vector<std::string>>>;

Lines lines_of(const std::string& text, char* separator = nullptr,
               CsvText::Records records = CsvText::Records::lines) {
  CsvText csv(text, "t.csv", records);
  Lines out;
  while (csv.next()) out.push_back({csv.line(), csv.cells()});
  if (separator) *separator = csv.separator();
  return out;
}

std::string refusal(const std::string& text) {
  try {
    lines_of(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(CsvText, DialectsSplitToTheSameCells) {
  const Lines expected{{1, {"x", "changed"}}, {2, {"0.5", "1"}}, {3, {"a, b", "0"}}};
  for (const std::string text : {
           "x,changed\n0.5,1\n\"a, b\",0\n",
           "\"x\",\"changed\"\r\n\"0.5\",\"1\"\r\n\"a, b\",0\r\n",
           "x;changed\n0.5;1\na, b;0\n",
           "x\tchanged\n0.5\t1\na, b\t0\n",
           "x,changed\r0.5,1\r\"a, b\",0",
           "\xEF\xBB\xBFx , changed\n 0.5,1 \n\"a, b\" ,0\n",
       }) {
    SCOPED_TRACE(text);
    EXPECT_EQ(lines_of(text), expected);
  }
}

TEST(CsvText, ACommentAfterTheValuesEndsTheLineButNotInsideQuotes) {
  char separator = 0;
  EXPECT_EQ(lines_of("# corners\nlon,lat # degrees\n12.5,55.1 # corner\n  # indented\n\n"
                     "12.6,55.1#east\n",
                     &separator),
            (Lines{{2, {"lon", "lat"}}, {3, {"12.5", "55.1"}}, {6, {"12.6", "55.1"}}}));
  EXPECT_EQ(separator, ',');
  // A '#' inside quotes is text; a comment after a quoted cell ends the line.
  EXPECT_EQ(lines_of("name,lon\n\"plot #4, north\",12.5 # here\n\"#\",\"1\" #\n"),
            (Lines{{1, {"name", "lon"}}, {2, {"plot #4, north", "12.5"}}, {3, {"#", "1"}}}));
  // The comment does not decide the separator: "12,5;55,1 # a, b" is ';' with decimal commas.
  EXPECT_EQ(lines_of("12,5;55,1 # a, b\n", &separator), (Lines{{1, {"12,5", "55,1"}}}));
  EXPECT_EQ(separator, ';');
  EXPECT_EQ(CsvText::number("12,5", separator), 12.5);
  EXPECT_EQ(lines_of("a\tb # c;d\n", &separator), (Lines{{1, {"a", "b"}}}));
  EXPECT_EQ(separator, '\t');
}

TEST(CsvText, NumbersAndDecimalCommas) {
  EXPECT_EQ(CsvText::number("+12.5", ','), 12.5);
  EXPECT_EQ(CsvText::number("-33,898203378", ';'), -33.898203378);
  EXPECT_FALSE(CsvText::number("12,5", ','));
  EXPECT_FALSE(CsvText::number("1.234,5", ';'));  // a thousands separator is not guessed at
  EXPECT_FALSE(CsvText::number("", ','));
  EXPECT_FALSE(CsvText::number("12.5 m", ','));
}

TEST(CsvText, MalformedQuotingNamesTheLineAndColumn) {
  EXPECT_EQ(refusal("a,b\n1,\"2\n"),
            "t.csv: line 2: column 2 opens a quote that the line does not close");
  EXPECT_EQ(refusal("a,b\n\"1\"5,2\n"), "t.csv: line 2: column 1 has text after its closing quote");
  // A quote a comment would have closed is still open: the '#' is inside it.
  EXPECT_EQ(refusal("a,b\r\r\"1 # x\n"),
            "t.csv: line 3: column 1 opens a quote that the line does not close");
}

// batch.csv as swath writes it: a quoted message holding line breaks (LF and CRLF) is one cell of
// one record, and an area name starting with '#' is text, quoted or not; each record is numbered
// by its first line.
TEST(CsvText, QuotedBreaksHoldLineBreaksInQuotesAndNoComments) {
  const std::string text =
      "area,directory,message\n"
      "#4 north,x-4,\"line one\nline two, \"\"quoted\"\"\"\n"
      "\"#plain\",d,\"a\r\nb\"\r\n"
      "\n"
      "last,e,\n";
  EXPECT_EQ(lines_of(text, nullptr, CsvText::Records::quoted_breaks),
            (Lines{{1, {"area", "directory", "message"}},
                   {2, {"#4 north", "x-4", "line one\nline two, \"quoted\""}},
                   {4, {"#plain", "d", "a\r\nb"}},
                   {7, {"last", "e", ""}}}));
  // Line by line the '#' starts a comment and the quote is open at the line's end.
  EXPECT_EQ(lines_of("name,dir\n#4 north,x-4\n"), (Lines{{1, {"name", "dir"}}}));
  EXPECT_EQ(refusal("m\n\"a\nb\"\n"),
            "t.csv: line 2: column 1 opens a quote that the line does not close");
  try {
    lines_of("a,b\n1,\"2\n3\n", nullptr, CsvText::Records::quoted_breaks);
    ADD_FAILURE() << "accepted a quote never closed";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "t.csv: line 2: column 2 opens a quote that the text does not close");
  }
}

// whitespace_fields against reading std::string after std::string from an istringstream (the WPL
// reader's former way), on random lines of every C-locale white-space character, bytes above 127,
// runs of separators at both ends, empty lines (fixed seed).
TEST(WhitespaceFields, AreWhatAStreamReads) {
  std::mt19937 rng(110);
  const std::string alphabet =
      std::string(" \t\n\v\f\r") + "0123456789.-+eE,;x#\"" + "\xc3\xa9\xff";
  for (int trial = 0; trial < 20000; ++trial) {
    std::string line;
    for (int k = static_cast<int>(rng() % 60); k > 0; --k) {
      // Mostly runs of one kind, so that fields and separators both repeat.
      const char c = alphabet[rng() % alphabet.size()];
      line.append(1 + rng() % 3, c);
    }
    std::istringstream in(line);
    std::vector<std::string> streamed;
    for (std::string field; in >> field;) streamed.push_back(field);
    const std::vector<std::string_view> fields = whitespace_fields(line);
    ASSERT_EQ(fields.size(), streamed.size()) << "trial " << trial;
    for (std::size_t k = 0; k < fields.size(); ++k)
      ASSERT_EQ(std::string(fields[k]), streamed[k]) << "trial " << trial << " field " << k;
  }
}

// next_line against std::getline on random texts of '\n', '\r', spaces and letters (empty lines, a
// last line with and without its '\n', an empty text): the same lines, the same count.
TEST(NextLine, GivesTheLinesGetlineGives) {
  std::mt19937_64 rng(55);
  for (int i = 0; i < 3000; ++i) {
    std::string text;
    for (int k = std::uniform_int_distribution<int>(0, 12)(rng); k > 0; --k)
      text += "\n\n\r ab"[std::uniform_int_distribution<int>(0, 5)(rng)];
    std::istringstream in(text);
    std::vector<std::string> expected, got;
    for (std::string line; std::getline(in, line);) expected.push_back(line);
    std::size_t at = 0;
    for (std::string_view line; next_line(text, at, line);) got.emplace_back(line);
    ASSERT_EQ(got, expected) << "text of " << text.size() << " bytes, case " << i;
  }
}

}  // namespace
}  // namespace swath::base
