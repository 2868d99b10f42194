#pragma once
// Text for other programs: words for a POSIX shell (the command lines `swath batch --emit-jobs` and
// `swath-fleet sweep` print for GNU parallel or Slurm), CSV fields, and this program's own path.

#include <string>

namespace swath::apps {

/// `word` as one shell word: as it is when it holds only letters, digits and -_./,:=+@, else in
/// single quotes (a quote inside written '\''). Throws base::InputError for a word holding a
/// control character: a line break ends a job line whatever the quoting.
std::string shell_word(const std::string& word);

/// A CSV text field, in double quotes when it holds a comma, a quote or a line break (RFC 4180);
/// text a spreadsheet would run as a formula (starting with = + - @, a tab or CR) gets a leading
/// apostrophe. For text cells only: numbers are written as they are.
std::string csv_field(const std::string& text);

/// The absolute path of the running program (/proc/self/exe), or `fallback` when it cannot be
/// read.
std::string own_program_path(const std::string& fallback);

}  // namespace swath::apps
