// checksum.hpp — FNV-1a, the 64-bit Fowler–Noll–Vo hash, for the integrity of the files a
// run writes to be read back (a checkpoint, its journals) and for a scene's fingerprint.
//
// Not cryptographic: it tells a file cut short, a flipped byte or another scene from
// the expected one (every byte changes the hash through a multiplication by an odd
// prime modulo 2⁶⁴), not a forgery.  Incremental: fnv1a(b, fnv1a(a)) = fnv1a(a + b).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace cdyn {

constexpr std::uint64_t kFnv1aOffset = 14695981039346656037ull;

inline std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash = kFnv1aOffset) {
  for (unsigned char b : bytes) {
    hash ^= b;
    hash *= 1099511628211ull;  // the 64-bit FNV prime
  }
  return hash;
}

// The hash as 16 hexadecimal digits.
inline std::string hex(std::uint64_t hash) {
  static const char digits[] = "0123456789abcdef";
  std::string out(16, '0');
  for (int k = 15; k >= 0; --k, hash >>= 4) out[k] = digits[hash & 15];
  return out;
}

}  // namespace cdyn
