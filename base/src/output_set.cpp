#include "swath/base/output_set.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "swath/base/input_error.hpp"

namespace swath::base {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kManifestPrefix = ".swath-";
constexpr std::string_view kManifestSuffix = ".files";

[[noreturn]] void fail(const fs::path& path, const std::string& what) {
  throw std::runtime_error(path.string() + ": " + what + " (" + std::strerror(errno) + ")");
}

std::string manifest_name(const std::string& kind) {
  return std::string(kManifestPrefix) + kind + std::string(kManifestSuffix);
}

// ---- The signal side: temporaries to remove when SIGINT/SIGTERM/SIGHUP/SIGXFSZ end the process.
// Kept in fixed storage the handler can read without allocating (async-signal-safe): 4,096 paths
// (16 MiB) mapped on the first registration, not a static array. In .bss the table was scanned
// by LeakSanitizer at every sanitized process's exit (4,000 of its 9,400 page faults, ~0.06 s of
// CPU a process; the CLI tests start ~600), and a program that writes nothing needs none of it.

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGXFSZ};
constexpr std::size_t kMaxTemporaries = 4096;
using PathSlot = std::array<char, PATH_MAX>;
PathSlot* volatile g_temporaries = nullptr;  // kMaxTemporaries slots once mapped; never unmapped
volatile sig_atomic_t g_temporary_count = 0;
std::array<char, PATH_MAX> g_created_directory{};  // removed too when the set created it
struct sigaction g_previous[std::size(kCleanupSignals)];
int g_open_sets = 0;

extern "C" void remove_temporaries_and_die(int signal_number) {
  for (sig_atomic_t i = 0; i < g_temporary_count; ++i) ::unlink(g_temporaries[i].data());
  if (g_created_directory[0] != '\0') ::rmdir(g_created_directory.data());
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

// Blocks the cleanup signals for the life of the object (registry updates, the renames).
class SignalBlock {
 public:
  SignalBlock() {
    sigset_t set;
    sigemptyset(&set);
    for (const int s : kCleanupSignals) sigaddset(&set, s);
    ::pthread_sigmask(SIG_BLOCK, &set, &previous_);
  }
  ~SignalBlock() { ::pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  SignalBlock(const SignalBlock&) = delete;
  SignalBlock& operator=(const SignalBlock&) = delete;

 private:
  sigset_t previous_;
};

void copy_path(std::array<char, PATH_MAX>& to, const std::string& path) {
  const std::size_t n = std::min(path.size(), to.size() - 1);
  std::memcpy(to.data(), path.data(), n);
  to[n] = '\0';
}

void register_temporary(const std::string& path) {
  SignalBlock block;
  if (static_cast<std::size_t>(g_temporary_count) >= kMaxTemporaries)
    throw std::runtime_error("more than " + std::to_string(kMaxTemporaries) +
                             " files in one output set");
  if (g_temporaries == nullptr) {
    void* table = ::mmap(nullptr, sizeof(PathSlot) * kMaxTemporaries, PROT_READ | PROT_WRITE,
                         MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (table == MAP_FAILED) fail(path, "cannot map the table of temporary files");
    g_temporaries = static_cast<PathSlot*>(table);
  }
  copy_path(g_temporaries[g_temporary_count], path);
  g_temporary_count = g_temporary_count + 1;
}

void unregister_temporary(const std::string& path) {
  SignalBlock block;
  for (sig_atomic_t i = 0; i < g_temporary_count; ++i)
    if (path == g_temporaries[i].data()) {
      g_temporaries[i] = g_temporaries[g_temporary_count - 1];
      g_temporary_count = g_temporary_count - 1;
      return;
    }
}

void install_handlers() {
  SignalBlock block;
  if (g_open_sets++ > 0) return;
  for (std::size_t i = 0; i < std::size(kCleanupSignals); ++i) {
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_die;
    sigemptyset(&action.sa_mask);
    for (const int s : kCleanupSignals) sigaddset(&action.sa_mask, s);
    ::sigaction(kCleanupSignals[i], nullptr, &g_previous[i]);
    // A signal the caller ignores (SIGXFSZ in the killed-write test, SIGHUP under nohup) stays
    // ignored: then the write fails with an error instead, and the destructor cleans up.
    if (g_previous[i].sa_handler == SIG_IGN) continue;
    ::sigaction(kCleanupSignals[i], &action, nullptr);
  }
}

void restore_handlers() {
  SignalBlock block;
  if (--g_open_sets > 0) return;
  for (std::size_t i = 0; i < std::size(kCleanupSignals); ++i)
    ::sigaction(kCleanupSignals[i], &g_previous[i], nullptr);
  g_created_directory[0] = '\0';
}

// ---- Files.

std::function<std::string()>& suffix_source() {
  static std::function<std::string()> source;
  return source;
}

std::function<int(const char*, const char*)>& rename_function() {
  static std::function<int(const char*, const char*)> function;
  return function;
}

// std::rename, or the tests' stand-in (testing::set_rename_function()).
int rename_file(const char* from, const char* to) {
  return rename_function() ? rename_function()(from, to) : std::rename(from, to);
}

std::string random_suffix() {
  if (suffix_source()) return suffix_source()();
  std::uint64_t bits = 0;
  if (::getrandom(&bits, sizeof bits, 0) != static_cast<ssize_t>(sizeof bits)) {
    // No entropy source: time and address still make a name no one can plant in advance reliably,
    // and O_EXCL refuses a name that exists anyway.
    bits = static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()) ^
           reinterpret_cast<std::uintptr_t>(&bits);
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(bits));
  return text;
}

void write_all(int fd, std::string_view bytes, const std::string& path) {
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(path, "cannot write");
    }
    written += static_cast<std::size_t>(n);
  }
}

// The names a manifest lists (one per line after the comment line).
std::vector<std::string> read_manifest(const fs::path& path) {
  std::vector<std::string> names;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') names.push_back(line);
  return names;
}

std::string kind_of_manifest(const std::string& file_name) {
  if (file_name.size() <= kManifestPrefix.size() + kManifestSuffix.size() ||
      file_name.compare(0, kManifestPrefix.size(), kManifestPrefix) != 0 ||
      file_name.compare(file_name.size() - kManifestSuffix.size(), kManifestSuffix.size(),
                        kManifestSuffix) != 0)
    return {};
  return file_name.substr(kManifestPrefix.size(),
                          file_name.size() - kManifestPrefix.size() - kManifestSuffix.size());
}

bool plain_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
         name.find('\0') == std::string::npos && kind_of_manifest(name).empty() &&
         name.size() < 200;
}

// The process holding the flock on `dir` as /proc/locks lists it ("" if not found).
std::string holder_of(const fs::path& dir) {
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) return {};
  char device[64];
  std::snprintf(device, sizeof device, "%02x:%02x:%llu", major(st.st_dev), minor(st.st_dev),
                static_cast<unsigned long long>(st.st_ino));
  std::ifstream locks("/proc/locks");
  std::string line;
  while (std::getline(locks, line)) {
    std::istringstream fields(line);
    std::string number, type, advisory, access, pid, where;
    fields >> number >> type >> advisory >> access >> pid >> where;
    if (type == "FLOCK" && where == device && pid != std::to_string(::getpid())) return pid;
  }
  return {};
}

// The names this kind's manifest in `dir` lists (`own`) and those other kinds' list, each as
// "NAME\tKIND" (`foreign`).
void read_manifests(const fs::path& dir, const std::string& kind, std::vector<std::string>& own,
                    std::vector<std::string>& foreign) {
  std::error_code ec;
  for (const auto& item : fs::directory_iterator(dir, ec)) {
    const std::string other = kind_of_manifest(item.path().filename().string());
    if (other == kind) own = read_manifest(item.path());
    if (other.empty() || other == kind) continue;
    for (std::string& name : read_manifest(item.path()))
      foreign.push_back(std::move(name) + '\t' + other);
  }
}

// Names other kinds of set wrote here are not ours to replace. A file of that name that no
// manifest lists is the user's (or an older swath's, which wrote no manifest): replacing it, and
// removing it with the next set, would lose it (unless keep_unlisted is off). A directory in the
// way is switch_in()'s to say.
void refuse_theirs(const fs::path& dir, const std::string& kind, const std::string& name,
                   const std::vector<std::string>& own, const std::vector<std::string>& foreign,
                   const OutputSet::Options& options) {
  for (const std::string& entry : foreign) {
    const auto tab = entry.find('\t');
    if (entry.compare(0, tab, name) == 0 && tab == name.size())
      throw InputError(dir.string() + "/" + name + " belongs to the files of a swath " +
                       entry.substr(tab + 1) +
                       " in this directory; write into another directory instead");
  }
  if (!options.keep_unlisted) return;
  struct stat st {};
  const fs::path path = dir / name;
  if (::lstat(path.c_str(), &st) != 0 || S_ISDIR(st.st_mode) ||
      std::find(own.begin(), own.end(), name) != own.end())
    return;
  throw InputError(path.string() + ": a file swath did not write (no " + manifest_name(kind) +
                   " here lists it) would be replaced; " + options.unlisted_remedy);
}

}  // namespace

struct OutputSet::Entry {
  std::string name;
  std::string temporary;  // full path
  std::unique_ptr<Stream> stream;
};

OutputSet::OutputSet(fs::path directory, std::string kind)
    : OutputSet(std::move(directory), std::move(kind), Options{}) {}

OutputSet::OutputSet(fs::path directory, std::string kind, Options options)
    : directory_(std::move(directory)), kind_(std::move(kind)), options_(options) {
  if (kind_.empty() || !std::all_of(kind_.begin(), kind_.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
      }))
    throw std::logic_error("OutputSet: bad kind '" + kind_ + "'");
  std::error_code ec;
  if (directory_.empty()) directory_ = ".";
  if (!fs::exists(directory_, ec)) {
    fs::create_directories(directory_, ec);
    created_directory_ = !ec;
  }
  if (!fs::is_directory(directory_, ec))
    throw InputError(directory_.string() + ": cannot create the output directory" +
                     (ec ? " (" + ec.message() + ")" : " (a file of that name is in the way)"));
  install_handlers();
  if (created_directory_) copy_path(g_created_directory, directory_.string());
  // The lock is a flock on the directory itself: no lock file is left behind.
  lock_fd_ = ::open(directory_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_fd_ < 0) {
    const int saved = errno;
    restore_handlers();
    throw InputError(directory_.string() + ": cannot open the output directory (" +
                     std::strerror(saved) + ")");
  }
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(options_.lock_wait_s);
  while (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK && errno != EINTR) fail(directory_, "cannot lock");
    if (std::chrono::steady_clock::now() >= deadline) {
      const std::string pid = holder_of(directory_);
      ::close(lock_fd_);
      lock_fd_ = -1;
      restore_handlers();
      throw InputError(directory_.string() + ": another swath run" +
                       (pid.empty() ? std::string() : " (process " + pid + ")") +
                       " is writing into this directory; waited " +
                       std::to_string(static_cast<int>(options_.lock_wait_s)) +
                       " s. Try again when it has finished, or give another -o");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (::access(directory_.c_str(), W_OK) != 0) {
    const int saved = errno;
    ::close(lock_fd_);
    lock_fd_ = -1;
    restore_handlers();
    throw InputError(directory_.string() + ": cannot write into the output directory (" +
                     std::strerror(saved) + ")");
  }

  read_manifests(directory_, kind_, own_, foreign_);
}

OutputSet::~OutputSet() {
  for (const auto& e : entries_) {
    if (e->stream && e->stream->fd_ >= 0) ::close(e->stream->fd_);
    if (!committed_) ::unlink(e->temporary.c_str());
    unregister_temporary(e->temporary);
  }
  if (!committed_ && created_directory_) ::rmdir(directory_.c_str());  // only if still empty
  if (lock_fd_ >= 0) ::close(lock_fd_);                                // releases the lock
  restore_handlers();
}

void OutputSet::check_name(const std::string& name) const {
  if (!plain_name(name))
    throw InputError("'" + name + "' is not a plain file name for " + directory_.string());
  if (has(name))
    throw InputError(directory_.string() + "/" + name +
                     " would be written twice by this command (two outputs share the name); "
                     "choose another name");
  refuse_theirs(directory_, kind_, name, own_, foreign_, options_);
}

bool OutputSet::has(const std::string& name) const {
  return std::any_of(entries_.begin(), entries_.end(),
                     [&](const auto& e) { return e->name == name; });
}

std::vector<std::string> OutputSet::names() const {
  std::vector<std::string> out;
  for (const auto& e : entries_) out.push_back(e->name);
  return out;
}

OutputSet::Entry& OutputSet::open_entry(const std::string& name) {
  check_name(name);
  if (committed_) throw std::logic_error("OutputSet: file added after commit()");
  return create_entry(name);
}

OutputSet::Entry& OutputSet::create_entry(const std::string& name) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string temporary = (directory_ / ("." + name + ".tmp-" + random_suffix())).string();
    register_temporary(temporary);
    const int fd =
        ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) {
      const int saved = errno;
      unregister_temporary(temporary);
      errno = saved;
      if (saved == EEXIST || saved == ELOOP) continue;  // planted: draw another name
      fail(temporary, "cannot create");
    }
    auto entry = std::make_unique<Entry>();
    entry->name = name;
    entry->temporary = temporary;
    entry->stream.reset(new Stream(fd, temporary));
    entries_.push_back(std::move(entry));
    return *entries_.back();
  }
  errno = EEXIST;
  fail(directory_ / name, "cannot create a temporary file beside it");
}

void OutputSet::add(const std::string& name, std::string_view content) {
  Stream& s = *open_entry(name).stream;
  s << content;
  s.flush();
}

OutputSet::Stream& OutputSet::stream(const std::string& name) {
  return *open_entry(name).stream;
}

OutputSet::Stream& OutputSet::Stream::operator<<(std::string_view text) {
  buffer_.append(text);
  size_ += text.size();
  if (buffer_.size() >= (std::size_t{1} << 16)) flush();
  return *this;
}

void OutputSet::Stream::flush() {
  write_all(fd_, buffer_, path_);
  buffer_.clear();
}

// The renames, all or none. Each file the set replaces is kept first under a second name (a hard
// link beside it: the file itself never goes missing), so that a rename failing part way is
// undone: the files renamed so far get their old selves back, or are removed where there was
// none, and the set is refused with the old set as it was. A directory in the way of a file is
// found before anything changes (then no hard link is needed either). Where an old file could
// not be kept (a file system without hard links, FAT on a memory card; a file at its link limit)
// or put back, the refusal names it: it stays replaced.
void OutputSet::switch_in() {
  struct Switch {
    fs::path target;
    std::string kept;  ///< the old file's second name; empty: none kept
    bool had_old = false;
  };
  std::vector<Switch> switches;
  // Undoes the first `renamed` renames and removes the second names; the names it could not put
  // back.
  const auto undo = [&](std::size_t renamed) {
    std::string left;
    for (std::size_t i = 0; i < switches.size(); ++i) {
      const Switch& w = switches[i];
      std::string lost;  // why this one stays replaced
      if (i >= renamed) {
        if (!w.kept.empty()) ::unlink(w.kept.c_str());
      } else if (!w.kept.empty()) {
        if (std::rename(w.kept.c_str(), w.target.c_str()) != 0)
          lost = " (its old content kept as " + fs::path(w.kept).filename().string() + ")";
      } else if (w.had_old) {
        lost = " (its old content not kept: no hard links here)";
      } else if (::unlink(w.target.c_str()) != 0) {
        lost = " (it had none before)";
      }
      if (!lost.empty()) left += (left.empty() ? "" : ", ") + w.target.filename().string() + lost;
    }
    return left;
  };
  for (const auto& e : entries_) {
    Switch w{directory_ / e->name, {}, false};
    struct stat st {};
    if (::lstat(w.target.c_str(), &st) == 0) {
      w.had_old = true;
      if (S_ISDIR(st.st_mode)) {
        undo(0);
        throw InputError(w.target.string() +
                         ": a directory of that name is in the way of the file swath writes "
                         "there; nothing was changed (move it, or give another output directory)");
      }
      for (int attempt = 0; attempt < 100 && w.kept.empty(); ++attempt) {
        const std::string kept =
            (directory_ / ("." + e->name + ".old-" + random_suffix())).string();
        if (::link(w.target.c_str(), kept.c_str()) == 0)
          w.kept = kept;
        else if (errno != EEXIST)
          break;  // not kept: see above
      }
    }
    switches.push_back(std::move(w));
  }
  for (std::size_t k = 0; k < entries_.size(); ++k)
    if (rename_file(entries_[k]->temporary.c_str(), switches[k].target.c_str()) != 0) {
      const int saved = errno;
      const std::string left = undo(k);
      throw std::runtime_error(
          switches[k].target.string() + ": cannot replace it with the new file (" +
          std::strerror(saved) + "); " +
          (left.empty() ? "the old files are as they were"
                        : "the files renamed before it are back as they were, except " + left));
    }
  undo(0);  // the old files' second names only
}

// A run ended by SIGKILL or a power cut (no handler runs) can leave its hidden temporaries
// (`.NAME.tmp-SUFFIX`) and, if it was switching its set in, the old files' second names
// (`.NAME.old-SUFFIX`). Under the directory's lock no other swath is writing here, so any such
// name of a file of this set or of the set before it is a leftover of a run that did not finish:
// removed once the new set is in. A name of any other form, or of a file swath did not write, is
// the user's and stays.
void OutputSet::remove_leftovers(const std::vector<std::string>& listed,
                                 const std::vector<std::string>& old) const {
  constexpr std::size_t kTail = 5 + 16;  // ".tmp-" or ".old-", then random_suffix()'s 16 digits
  const auto ours = [&](const std::string& file) {
    if (file.size() <= 1 + kTail || file[0] != '.') return false;
    const std::string tail = file.substr(file.size() - kTail);
    if (tail.compare(0, 5, ".tmp-") != 0 && tail.compare(0, 5, ".old-") != 0) return false;
    if (!std::all_of(tail.begin() + 5, tail.end(),
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); }))
      return false;
    const std::string name = file.substr(1, file.size() - 1 - kTail);
    return std::find(listed.begin(), listed.end(), name) != listed.end() ||
           std::find(old.begin(), old.end(), name) != old.end() || name == manifest_name(kind_);
  };
  std::error_code ec;
  for (const auto& item : fs::directory_iterator(directory_, ec)) {
    const std::string file = item.path().filename().string();
    struct stat st {};
    if (ours(file) && ::lstat(item.path().c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
      ::unlink(item.path().c_str());
  }
}

void OutputSet::commit() {
  if (committed_) throw std::logic_error("OutputSet: commit() twice");
  const fs::path manifest = directory_ / manifest_name(kind_);
  const std::vector<std::string> old = read_manifest(manifest);
  std::vector<std::string> listed = names();
  if (options_.mode == Mode::amend)
    for (const std::string& n : old)
      if (std::find(listed.begin(), listed.end(), n) == listed.end()) listed.push_back(n);
  std::string manifest_text = "# the files swath's last " + kind_ + " wrote here\n";
  for (const std::string& n : listed) manifest_text += n + "\n";
  *create_entry(manifest_name(kind_)).stream << manifest_text;

  // Every file complete on disk before any is renamed: an error leaves the old set untouched.
  // Every file's write-back is started before any is waited for, so that the file system writes
  // and journals them together (one commit for the set, not one per file: fsync batched per plan).
  for (const auto& e : entries_) {
    Stream& s = *e->stream;
    s.flush();
#ifdef __linux__
    ::sync_file_range(s.fd_, 0, 0, SYNC_FILE_RANGE_WRITE);  // a hint: fsync() below decides
#endif
  }
  for (const auto& e : entries_) {
    Stream& s = *e->stream;
    const bool synced = ::fsync(s.fd_) == 0;
    const bool closed = ::close(s.fd_) == 0;
    s.fd_ = -1;
    if (!synced || !closed) fail(e->temporary, "cannot flush");
  }

  {
    SignalBlock block;  // a signal now would leave a mixed set
    switch_in();
    committed_ = true;
    if (options_.mode == Mode::replace)
      for (const std::string& n : old)
        if (std::find(listed.begin(), listed.end(), n) == listed.end() && plain_name(n))
          ::unlink((directory_ / n).c_str());
    remove_leftovers(listed, old);
    // The renames made durable through the directory's own descriptor, the one that holds the
    // lock (opened read-only with O_DIRECTORY, which fsync takes): no second open.
    ::fsync(lock_fd_);
  }
}

namespace testing {
void set_temporary_suffix_source(std::function<std::string()> source) {
  suffix_source() = std::move(source);
}
void set_rename_function(std::function<int(const char*, const char*)> rename) {
  rename_function() = std::move(rename);
}
}  // namespace testing

void write_files_atomically(const fs::path& directory,
                            const std::vector<std::pair<std::string, std::string>>& files,
                            const std::string& kind, bool keep_unlisted) {
  OutputSet set(directory, kind, {OutputSet::Mode::replace, 10.0, keep_unlisted});
  for (const auto& [name, content] : files) set.add(name, content);
  set.commit();
}

void check_output_names(const fs::path& directory, const std::string& kind,
                        const std::vector<std::string>& names, const OutputSet::Options& options) {
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) return;  // nothing there to replace
  std::vector<std::string> own, foreign;
  read_manifests(directory, kind, own, foreign);
  for (const std::string& name : names) refuse_theirs(directory, kind, name, own, foreign, options);
}

}  // namespace swath::base
