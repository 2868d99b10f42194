#pragma once
// The set of files a command writes into its output directory, switched in as a whole
// (docs/reliability.md).
//
// - Each file goes to a temporary in the same directory, created exclusively with a random name
//   (O_CREAT | O_EXCL | O_NOFOLLOW: a planted file or symlink is never opened, another name is
//   drawn) and flushed; nothing is renamed before every file of the set is complete.
// - The directory is locked (flock on the directory itself) for the life of the set: a second run
//   into it waits up to `lock_wait_s`, then is refused naming the process that holds it.
// - A manifest per set kind (DIR/.swath-<kind>.files) lists what the set wrote. The next set of
//   the same kind removes the files the old manifest lists and the new set does not write (stale
//   drone-3.plan after a re-plan with two drones); swath never removes a file it did not write.
//   A file another kind's manifest lists is never replaced (swath-energy run -o into a plan
//   directory is refused instead of overwriting the plan's summary.json). A file no manifest lists
//   is not replaced either (the user's photos.csv or trace.csv in an output directory), unless the
//   set is told to (keep_unlisted false: a file the user named on the command line).
// - SIGINT, SIGTERM and SIGHUP are blocked while the files are renamed into place, so a signal
//   leaves the whole old set or the whole new one; a rename that fails part way (a directory in the
//   way) is undone, the old files back under their names (kept as hard links meanwhile); a SIGINT
//   or SIGTERM before that removes the temporaries (and a directory the set created) and ends the
//   process as the signal would.
// - A set that is destroyed without commit() leaves the directory as it was (a refusal after the
//   set was opened writes nothing, and an output directory it had to create is removed again).

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace swath::base {

class OutputSet {
 public:
  /// What a set does to the files of its kind already in the directory.
  enum class Mode {
    replace,  ///< the new set is the whole set: stale files of the old manifest are removed
    amend,    ///< the files are added to (or replace files of) the existing set of that kind
  };

  struct Options {
    Mode mode = Mode::replace;
    double lock_wait_s = 10.0;  ///< how long to wait for another run's lock, seconds
    /// Refuse a name whose file is there but listed in no manifest of the directory (the user's
    /// own, or one an older swath wrote without a manifest) instead of replacing it.
    bool keep_unlisted = true;
    /// The end of that refusal's sentence: what the user can do instead.
    const char* unlisted_remedy = "move it, or choose another -o";
  };

  /// Opens `directory` (created if missing) for a set of `kind` ("plan", "energy-run": letters,
  /// digits and '-'), locking it. Throws InputError when the directory cannot be created or is
  /// held by another run past the wait, std::runtime_error for other system failures.
  OutputSet(std::filesystem::path directory, std::string kind, Options options);
  OutputSet(std::filesystem::path directory, std::string kind);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// A file written piece by piece into its temporary (memory stays flat however long it is).
  class Stream {
   public:
    Stream& operator<<(std::string_view text);
    Stream& operator<<(char c) { return *this << std::string_view(&c, 1); }
    /// Bytes written so far.
    std::size_t size() const { return size_; }

   private:
    friend class OutputSet;
    explicit Stream(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
    void flush();
    int fd_ = -1;
    std::string path_;
    std::string buffer_;
    std::size_t size_ = 0;
  };

  /// Adds a file with its whole content. Throws InputError for a name that is not a plain file
  /// name, that the set already has, that another kind's manifest in the directory lists, or
  /// (keep_unlisted) whose file is there and listed in no manifest.
  void add(const std::string& name, std::string_view content);
  /// Adds a file to be written piece by piece; the reference stays valid until commit(). Same
  /// refusals as add().
  Stream& stream(const std::string& name);
  /// Whether the set has a file of this name already.
  bool has(const std::string& name) const;
  /// The names added so far, in order.
  std::vector<std::string> names() const;

  /// Flushes every file, switches them in (renames, signals blocked), removes the stale files of
  /// the old manifest (Mode::replace) and writes the new manifest. Throws std::runtime_error
  /// (path and the system's reason) if a file cannot be written; the old set is then untouched.
  void commit();

  const std::filesystem::path& directory() const { return directory_; }

 private:
  struct Entry;
  void check_name(const std::string& name) const;
  Entry& open_entry(const std::string& name);    ///< checked name
  Entry& create_entry(const std::string& name);  ///< the temporary for any name
  /// Renames every temporary onto its name, all or none (signals blocked by the caller).
  void switch_in();
  /// Removes the hidden temporaries and kept old files a killed run left of these names.
  void remove_leftovers(const std::vector<std::string>& listed,
                        const std::vector<std::string>& old) const;

  std::filesystem::path directory_;
  std::string kind_;
  Options options_;
  int lock_fd_ = -1;
  bool created_directory_ = false;
  bool committed_ = false;
  std::vector<std::unique_ptr<Entry>> entries_;
  std::vector<std::string> foreign_;  ///< names other kinds' manifests list
  std::vector<std::string> own_;      ///< names this kind's manifest lists
};

namespace testing {
/// Replaces the random suffix of temporary names (tests plant files at the names it will draw);
/// an empty function restores the random one.
void set_temporary_suffix_source(std::function<std::string()> source);
/// Replaces std::rename for the renames that switch a set's files in (tests make one fail part
/// way, as a file system can); an empty function restores std::rename.
void set_rename_function(std::function<int(const char*, const char*)> rename);
}  // namespace testing

/// Writes `files` (name, content) as one set of `kind` (OutputSet, Mode::replace) and commits it.
void write_files_atomically(const std::filesystem::path& directory,
                            const std::vector<std::pair<std::string, std::string>>& files,
                            const std::string& kind = "files", bool keep_unlisted = true);

/// Refuses `names` as a set of `kind` in `directory` would refuse them (another kind's files; with
/// keep_unlisted, files no manifest lists), writing and locking nothing: a command checks its
/// output before work it cannot redo (a flight over MAVLink) or before its first of several sets.
/// Throws InputError; a directory that is not there yet refuses nothing.
void check_output_names(const std::filesystem::path& directory, const std::string& kind,
                        const std::vector<std::string>& names,
                        const OutputSet::Options& options = {});

}  // namespace swath::base
