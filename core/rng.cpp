#include "core/rng.h"

namespace dp::core {

uint64_t mix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

Rng::Rng(uint64_t s, uint64_t stream) { seed(s, stream); }

void Rng::seed(uint64_t s, uint64_t stream) {
  const uint64_t h = mix64(mix64(s) ^ (stream * 0xd1b54a32d192ed03ull + 0x8cb92ba72f3d8dd7ull));
  m_engine.seed(static_cast<uint32_t>(h ^ (h >> 32)));
}

}  // namespace dp::core
