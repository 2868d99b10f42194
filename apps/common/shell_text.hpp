#pragma once
// Text for other programs: words for a POSIX shell (the command lines `swath batch --emit-jobs` and
// `swath-fleet sweep` print for GNU parallel or Slurm), CSV fields, and this program's own path.

#include <string>

namespace swath::apps {

/// `word` as one shell word: as it is when it holds only letters, digits and -_./,:=+@, else in
/// single quotes (a quote inside written '\'').
std::string shell_word(const std::string& word);

/// A CSV field, in double quotes when it holds a comma, a quote or a line break (RFC 4180).
std::string csv_field(const std::string& text);

/// The absolute path of the running program (/proc/self/exe), or `fallback` when it cannot be
/// read.
std::string own_program_path(const std::string& fallback);

}  // namespace swath::apps
