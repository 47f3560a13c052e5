// Content hashes for cache keys: SHA-256 (FIPS 180-4) through OpenSSL's libcrypto (Debian
// libssl-dev, already pulled in by libhdf5-dev and petsc-dev). A cryptographic hash, not a fast
// non-cryptographic one, because a key must not collide for two different inputs of a study
// (a 64-bit FNV-1a would, for adversarial or merely unlucky files), and because libcrypto's
// SHA-NI/AVX2 code hashes about 1-2 GB/s, so hashing the mesh and pressure files costs little
// next to one solver run.
#pragma once
#include <string>
#include <string_view>

namespace ugs::runner {

// SHA-256 of the bytes, as 64 lower-case hex digits.
std::string sha256_hex(std::string_view bytes);
// SHA-256 of a file's bytes (read in 1 MiB pieces); InputError(path) if it cannot be read.
std::string sha256_file_hex(const std::string& path);

}  // namespace ugs::runner
