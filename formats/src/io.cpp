#include "ugs/formats/io.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <mutex>
#include <set>

namespace ugs {

namespace {
constexpr std::size_t kBufferSize = 1 << 20;

std::string errno_text() { return std::strerror(errno); }
}  // namespace

std::unique_ptr<InputStream> InputStream::open(const std::string& path, const std::string& expected) {
  std::unique_ptr<InputStream> in(new InputStream);
  if (path.empty() || path == "-") {
    in->file_ = stdin;
    in->name_ = "<stdin>";
  } else {
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
      throw InputError(path, "is a directory (expected " + expected + ")");
    in->file_ = std::fopen(path.c_str(), "rb");
    if (!in->file_) throw InputError(path, "cannot open: " + errno_text());
    in->owns_file_ = true;
    in->name_ = path;
  }
  // (Also for stdin, which a shell can open on a directory.)
  struct stat st {};
  if (fstat(fileno(in->file_), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw InputError(in->name_, "is a directory (expected " + expected + ")");
    if (S_ISREG(st.st_mode)) in->size_ = static_cast<std::uint64_t>(st.st_size);
  }
  in->buf_.resize(kBufferSize);
  return in;
}

std::unique_ptr<InputStream> InputStream::from_string(std::string data, std::string name) {
  std::unique_ptr<InputStream> in(new InputStream);
  in->name_ = std::move(name);
  in->size_ = data.size();
  in->buf_.assign(data.begin(), data.end());
  in->end_ = in->buf_.size();
  in->eof_ = true;  // nothing more to fill
  return in;
}

InputStream::~InputStream() {
  if (owns_file_ && file_) std::fclose(file_);
}

std::optional<std::uint64_t> InputStream::remaining() const {
  if (!size_) return std::nullopt;
  return *size_ > offset_ ? *size_ - offset_ : 0;
}

bool InputStream::fill() {
  if (pos_ < end_) return true;
  if (eof_ || !file_) return false;
  pos_ = 0;
  end_ = std::fread(buf_.data(), 1, buf_.size(), file_);
  if (end_ == 0) {
    if (std::ferror(file_)) throw InputError(name_, "read error: " + errno_text());
    eof_ = true;
    return false;
  }
  return true;
}

int InputStream::peek() {
  if (!fill()) return -1;
  return static_cast<unsigned char>(buf_[pos_]);
}

bool InputStream::getline(std::string& out) {
  out.clear();
  bool any = false;
  while (fill()) {
    any = true;
    const char* start = buf_.data() + pos_;
    const char* nl = static_cast<const char*>(std::memchr(start, '\n', end_ - pos_));
    const std::size_t n = nl ? static_cast<std::size_t>(nl - start) : end_ - pos_;
    out.append(start, n);
    pos_ += n;
    offset_ += n;
    if (nl) {
      ++pos_;
      ++offset_;
      ++line_;
      break;
    }
  }
  if (!out.empty() && out.back() == '\r') out.pop_back();
  return any;
}

void InputStream::read_exact(void* dst, std::size_t n) {
  char* d = static_cast<char*>(dst);
  while (n > 0) {
    if (!fill()) throw error_at_byte("unexpected end of input (truncated file?)");
    const std::size_t k = std::min(n, end_ - pos_);
    std::memcpy(d, buf_.data() + pos_, k);
    pos_ += k;
    offset_ += k;
    d += k;
    n -= k;
  }
}

void InputStream::skip_whitespace() {
  while (fill()) {
    const char c = buf_[pos_];
    if (c == '\n') ++line_;
    else if (c != ' ' && c != '\t' && c != '\r') return;
    ++pos_;
    ++offset_;
  }
}

std::string_view InputStream::token() {
  skip_whitespace();
  token_.clear();
  while (fill()) {
    const char* start = buf_.data() + pos_;
    std::size_t k = 0;
    const std::size_t avail = end_ - pos_;
    while (k < avail) {
      const char c = start[k];
      if (c == ' ' || c == '\n' || c == '\t' || c == '\r') break;
      ++k;
    }
    token_.append(start, k);
    pos_ += k;
    offset_ += k;
    if (k < avail) break;
    if (token_.size() > 4096) throw error("token longer than 4096 characters");
  }
  return token_;
}

InputError InputStream::error(const std::string& message) const {
  return InputError(name_ + ":" + std::to_string(line_), message);
}

InputError InputStream::error_at_byte(const std::string& message) const {
  return InputError(name_ + ": byte " + std::to_string(offset_), message);
}

// ---- atomic output ---------------------------------------------------------

namespace {
std::mutex g_tmp_mutex;
std::set<std::string>& pending_temporaries() {
  static std::set<std::string> s;
  return s;
}
// Fixed-size copy read by the signal handler (no allocation there).
constexpr int kMaxTmp = 64;
char g_tmp_paths[kMaxTmp][4096];
volatile std::sig_atomic_t g_tmp_used[kMaxTmp];

void register_tmp(const std::string& p) {
  std::lock_guard lock(g_tmp_mutex);
  pending_temporaries().insert(p);
  for (int i = 0; i < kMaxTmp; ++i)
    if (!g_tmp_used[i] && p.size() < sizeof g_tmp_paths[i]) {
      std::memcpy(g_tmp_paths[i], p.c_str(), p.size() + 1);
      g_tmp_used[i] = 1;
      break;
    }
}
void unregister_tmp(const std::string& p) {
  std::lock_guard lock(g_tmp_mutex);
  pending_temporaries().erase(p);
  for (int i = 0; i < kMaxTmp; ++i)
    if (g_tmp_used[i] && p == g_tmp_paths[i]) g_tmp_used[i] = 0;
}
extern "C" void cleanup_on_signal(int sig) {
  for (int i = 0; i < kMaxTmp; ++i)
    if (g_tmp_used[i]) ::unlink(g_tmp_paths[i]);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}
}  // namespace

void remove_uncommitted_outputs() {
  for (int i = 0; i < kMaxTmp; ++i)
    if (g_tmp_used[i]) ::unlink(g_tmp_paths[i]);
}

void install_output_cleanup_handlers() {
  std::signal(SIGINT, cleanup_on_signal);
  std::signal(SIGTERM, cleanup_on_signal);
  std::signal(SIGHUP, cleanup_on_signal);
}

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
  if (path_.empty() || path_ == "-") {
    to_stdout_ = true;
    file_ = stdout;
    path_ = "<stdout>";
    return;
  }
  std::string tmpl = path_ + ".tmp.XXXXXX";
  std::vector<char> name(tmpl.begin(), tmpl.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw InputError(path_, "cannot create output: " + errno_text());
  ::fchmod(fd, 0644);
  tmp_ = name.data();
  register_tmp(tmp_);
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    ::close(fd);
    ::unlink(tmp_.c_str());
    unregister_tmp(tmp_);
    throw InputError(path_, "cannot open output: " + errno_text());
  }
}

OutputFile::~OutputFile() {
  if (to_stdout_) return;
  if (!committed_) {
    if (file_) std::fclose(file_);
    ::unlink(tmp_.c_str());
    unregister_tmp(tmp_);
  }
}

void OutputFile::write(const void* data, std::size_t n) {
  if (n && std::fwrite(data, 1, n, file_) != n)
    throw ComputeError(path_ + ": write failed: " + errno_text());
}

void OutputFile::commit() {
  if (committed_) return;
  if (to_stdout_) {
    if (std::fflush(stdout) != 0) throw ComputeError("<stdout>: write failed: " + errno_text());
    committed_ = true;
    return;
  }
  const bool bad = std::fflush(file_) != 0 || std::ferror(file_);
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (bad || close_failed) throw ComputeError(path_ + ": write failed: " + errno_text());
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0)
    throw ComputeError(path_ + ": cannot rename temporary output: " + errno_text());
  unregister_tmp(tmp_);
  committed_ = true;
}

}  // namespace ugs
