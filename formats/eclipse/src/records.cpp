// The record walk of records.hpp: only what the format fixes, nothing of what the arrays mean.
#include "records.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::eclipse {
namespace {

struct ItemType {
  std::int64_t bytes = 0;     // per item
  std::int64_t per_record = 0; // items per data record at most
};

// Item size and record length of a header's type; `ok` false for a type EclIO does not know.
bool item_type(const char t[4], ItemType& out) {
  const std::string s(t, 4);
  if (s == "INTE" || s == "REAL" || s == "LOGI") out = {4, 1000};
  else if (s == "DOUB") out = {8, 1000};
  else if (s == "CHAR") out = {8, 105};
  else if (s == "MESS") out = {0, 0};
  else if (s[0] == 'C' && std::isdigit(static_cast<unsigned char>(s[1])) && std::isdigit(static_cast<unsigned char>(s[2])) &&
           std::isdigit(static_cast<unsigned char>(s[3])) && std::stoi(s.substr(1)) > 0)
    out = {std::stoi(s.substr(1)), 105};  // C0nn: strings of nn characters
  else return false;
  return true;
}

std::int32_t big_endian(const unsigned char b[4]) {
  const std::uint32_t u = (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) | b[3];
  std::int32_t v;
  std::memcpy(&v, &u, 4);
  return v;
}

class Walk {
public:
  explicit Walk(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw InputError(path, "cannot be opened");
    std::error_code ec;
    size_ = static_cast<std::int64_t>(std::filesystem::file_size(path, ec));
    if (ec) throw InputError(path, "cannot be opened (no file size)");
  }
  bool at_end() const { return pos_ == size_; }
  std::int64_t pos() const { return pos_; }

  // One record: its length (checked against its tail marker and the file's end); the bytes are read
  // into `body` when it is given (a header), skipped otherwise.
  std::int64_t record(const std::string& what, unsigned char* body = nullptr, std::int64_t body_size = 0) {
    const std::int64_t start = pos_;
    if (size_ - pos_ < 4) fail(start, fmt::format("{}: the file ends inside a record marker", what));
    const std::int32_t n = marker();
    if (n < 0 || n > size_ - pos_ - 4)
      fail(start, fmt::format("{}: record of {} bytes, but {} bytes are left in the file", what, n, size_ - pos_));
    if (body) {
      if (n != body_size) fail(start, fmt::format("{}: record of {} bytes (expected {})", what, n, body_size));
      in_.read(reinterpret_cast<char*>(body), n);
    } else {
      in_.seekg(n, std::ios::cur);
    }
    pos_ += n;
    const std::int32_t tail = marker();
    if (tail != n) fail(start, fmt::format("{}: record of {} bytes ends with the marker {}", what, n, tail));
    return n;
  }

  [[noreturn]] void fail(std::int64_t at, const std::string& what) const {
    throw InputError(path_, fmt::format("cannot be read as ECLIPSE binary output: byte {}: {} (the file is cut short or damaged)", at, what));
  }

private:
  std::int32_t marker() {
    unsigned char b[4];
    in_.read(reinterpret_cast<char*>(b), 4);
    if (!in_) fail(pos_, "the file cannot be read here");
    pos_ += 4;
    return big_endian(b);
  }

  std::string path_;
  std::ifstream in_;
  std::int64_t size_ = 0, pos_ = 0;
};

// Text of the file as it goes into a message: bytes that are not printable ASCII become '?'.
std::string printable(const unsigned char* s, std::size_t n) {
  std::string out;
  for (std::size_t i = 0; i < n; ++i) out += std::isprint(s[i]) ? static_cast<char>(s[i]) : '?';
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}
std::string printable(const std::string& s) { return printable(reinterpret_cast<const unsigned char*>(s.data()), s.size()); }

void check_binary_records(const std::string& path) {
  Walk w(path);
  if (w.at_end()) throw InputError(path, "empty file (expected ECLIPSE binary output)");
  while (!w.at_end()) {
    const std::int64_t at = w.pos();
    unsigned char h[16];
    w.record("array header", h, 16);
    const std::string name = printable(h, 8);
    std::int64_t count = big_endian(h + 8);
    char type[4];
    std::memcpy(type, h + 12, 4);
    if (std::string(type, 4) == "X231") {
      // Arrays of 2^31 items or more: a first header holds -(count / 2^31), the next the rest.
      const std::int64_t high = -count;
      unsigned char h2[16];
      w.record(fmt::format("array {}: second header", name), h2, 16);
      if (std::memcmp(h, h2, 8) != 0 || high < 0)
        w.fail(at, fmt::format("array {}: an X231 header not followed by the same array's header", name));
      count = big_endian(h2 + 8) + high * (std::int64_t{1} << 31);
      std::memcpy(type, h2 + 12, 4);
    }
    ItemType t;
    if (!item_type(type, t)) w.fail(at, fmt::format("array {}: unknown type '{}'", name, printable(reinterpret_cast<unsigned char*>(type), 4)));
    if (count < 0) w.fail(at, fmt::format("array {}: {} items", name, count));
    if (t.bytes == 0) {
      if (count != 0) w.fail(at, fmt::format("array {}: a MESS array of {} items (expected 0)", name, count));
      continue;
    }
    // The items follow in records of at most per_record items each (writers fill all but the last;
    // EclIO reads any split, and so does this walk).
    for (std::int64_t left = count; left > 0;) {
      const std::int64_t rec_at = w.pos();
      const std::int64_t n = w.record(fmt::format("array {} ({} items)", name, count));
      if (n == 0 || n % t.bytes != 0 || n / t.bytes > std::min(left, t.per_record))
        w.fail(rec_at, fmt::format("array {} ({} items, {} left): data record of {} bytes (expected a multiple of {}, at most {})",
                                   name, count, left, n, t.bytes, std::min(left, t.per_record) * t.bytes));
      left -= n / t.bytes;
    }
  }
}


// Bytes of a formatted array's items as EclIO computes them (EclUtil.cpp sizeOnDiskFormatted):
// blocks of at most `block` items, `columns` items of `width` characters per line, each line and
// each block's last line ended by a newline.
std::int64_t formatted_size(std::int64_t count, std::int64_t block, std::int64_t columns, std::int64_t width) {
  const auto block_bytes = [&](std::int64_t items) { return items * width + items / columns + (items % columns > 0 ? 1 : 0); };
  return (count / block) * block_bytes(block) + block_bytes(count % block);
}

void check_formatted_records(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot be opened");
  std::error_code ec;
  const auto size = static_cast<std::int64_t>(std::filesystem::file_size(path, ec));
  if (ec) throw InputError(path, "cannot be opened (no file size)");
  if (size == 0) throw InputError(path, "empty file (expected ECLIPSE formatted output)");
  const auto fail = [&](std::int64_t at, const std::string& what) {
    throw InputError(path, fmt::format("cannot be read as ECLIPSE formatted output: byte {}: {} (the file is cut short or damaged)", at, what));
  };
  std::int64_t pos = 0;
  std::string line;
  while (pos < size) {
    in.seekg(pos);
    if (!std::getline(in, line)) fail(pos, "the file cannot be read here");
    const std::int64_t at = pos;
    pos += static_cast<std::int64_t>(line.size()) + (in.eof() ? 0 : 1);
    // 'NAME    '  count 'TYPE', as EclIO parses it (the first four quotes).
    std::size_t q[4];
    std::size_t from = 0;
    for (auto& qi : q) {
      qi = line.find('\'', from);
      if (qi == std::string::npos) fail(at, "expected an array header 'NAME' count 'TYPE' here");
      from = qi + 1;
    }
    const std::string raw_name = line.substr(q[0] + 1, q[1] - q[0] - 1), type = line.substr(q[2] + 1, q[3] - q[2] - 1);
    const std::string name = printable(raw_name);
    const std::string count_text = line.substr(q[1] + 1, q[2] - q[1] - 1);
    std::int64_t count = 0;
    {
      std::size_t used = 0;
      try {
        count = std::stoll(count_text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || count_text.find_first_not_of(" ", used) != std::string::npos)
        fail(at, fmt::format("array '{}': item count '{}' is not an integer", name, printable(count_text)));
    }
    if (raw_name.size() != 8) fail(at, fmt::format("array '{}': the name is not 8 characters", name));
    if (count < 0) fail(at, fmt::format("array {}: {} items", name, count));
    std::int64_t columns = 0, width = 0, block = 1000;
    if (type == "INTE") columns = 6, width = 12;
    else if (type == "REAL") columns = 4, width = 17;
    else if (type == "DOUB") columns = 3, width = 23;
    else if (type == "LOGI") columns = 25, width = 3;
    else if (type == "CHAR") columns = 7, width = 11, block = 105;
    else if (type == "MESS") {
      if (count != 0) fail(at, fmt::format("array {}: a MESS array of {} items (expected 0)", name, count));
      continue;
    } else if (type.size() == 4 && type[0] == 'C' && std::isdigit(static_cast<unsigned char>(type[1])) &&
               std::isdigit(static_cast<unsigned char>(type[2])) && std::isdigit(static_cast<unsigned char>(type[3]))) {
      // C0nn strings; EclIO puts 80 / (nn + 3) of them on a line, none when nn > 77.
      const int nn = std::stoi(type.substr(1));
      if (nn < 1 || nn > 77) fail(at, fmt::format("array {}: strings of {} characters (type {}; expected 1 to 77)", name, nn, printable(type)));
      columns = 80 / (nn + 3), width = nn + 3, block = 105;
    } else {
      fail(at, fmt::format("array {}: unknown type '{}'", name, printable(type)));
    }
    if (count > size) fail(at, fmt::format("array {}: {} items, more than the file's {} bytes", name, count, size));
    const std::int64_t bytes = formatted_size(count, block, columns, width);
    if (bytes > size - pos)
      fail(at, fmt::format("array {}: {} items take {} bytes, but {} are left in the file", name, count, bytes, size - pos));
    pos += bytes;
  }
}

}  // namespace

bool is_formatted(const std::string& path) {
  const auto dot = path.find_last_of('.');
  return dot != std::string::npos && dot + 1 < path.size() && std::strchr("ABCFGH", path[dot + 1]) != nullptr;
}

void check_records(const std::string& path) {
  if (is_formatted(path))
    check_formatted_records(path);
  else
    check_binary_records(path);
}

}  // namespace ugs::eclipse
