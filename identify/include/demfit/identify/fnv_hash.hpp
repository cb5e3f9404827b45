#pragma once
// FNV-1a 64 (Fowler–Noll–Vo): the one hash of the store's row checksums and the fill cache's keys
// and checksums. Detects accidental edits and damage; it is no signature.
#include <cstdint>
#include <string_view>

namespace demfit::identify {

inline constexpr std::uint64_t kFnvOffsetBasis = 14695981039346656037ull;
inline constexpr std::uint64_t kFnvPrime = 1099511628211ull;

/// The hash of `bytes` continued from `hash` (start: kFnvOffsetBasis).
inline std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash = kFnvOffsetBasis) {
  for (const unsigned char c : bytes) hash = (hash ^ c) * kFnvPrime;
  return hash;
}

}  // namespace demfit::identify
