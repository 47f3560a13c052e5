#include "ugs/runner/content_hash.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <openssl/evp.h>

#include "ugs/formats/error.hpp"

namespace ugs::runner {

namespace {

class Sha256 {
public:
  Sha256() : ctx_(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
    if (!ctx_ || EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr) != 1)
      throw ComputeError("SHA-256: cannot initialise libcrypto's digest");
  }
  void update(const void* data, std::size_t n) {
    if (n > 0 && EVP_DigestUpdate(ctx_.get(), data, n) != 1) throw ComputeError("SHA-256: digest update failed");
  }
  std::string hex() {
    unsigned char md[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    if (EVP_DigestFinal_ex(ctx_.get(), md, &len) != 1) throw ComputeError("SHA-256: digest failed");
    std::string s;
    s.reserve(2 * len);
    for (unsigned int i = 0; i < len; ++i) s += fmt::format("{:02x}", md[i]);
    return s;
  }

private:
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx_;
};

}  // namespace

std::string sha256_hex(std::string_view bytes) {
  Sha256 h;
  h.update(bytes.data(), bytes.size());
  return h.hex();
}

std::string sha256_file_hex(const std::string& path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!f) throw InputError(path, fmt::format("cannot read: {}", std::strerror(errno)));
  Sha256 h;
  std::vector<char> buf(1 << 20);
  for (;;) {
    const std::size_t n = std::fread(buf.data(), 1, buf.size(), f.get());
    h.update(buf.data(), n);
    if (n < buf.size()) {
      if (std::ferror(f.get())) throw InputError(path, fmt::format("cannot read: {}", std::strerror(errno)));
      break;
    }
  }
  return h.hex();
}

}  // namespace ugs::runner
