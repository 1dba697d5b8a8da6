#pragma once
/// @file
/// Random streams: each node gets its own stream derived only from the experiment seed and
/// the node's name, so adding a node or changing rates never changes another node's draws.
#include <cstdint>
#include <random>
#include <string_view>

namespace somasim {

/// 64-bit FNV-1a hash of a string (stable across platforms and runs, unlike std::hash).
constexpr std::uint64_t fnv1a64(std::string_view s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : s) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

/// One step of SplitMix64: a well-mixed 64-bit value from any 64-bit input.
constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// The seed of the stream of node `node_name` in an experiment with seed `experiment_seed`.
constexpr std::uint64_t node_stream_seed(std::uint64_t experiment_seed,
                                         std::string_view node_name) {
  return splitmix64(splitmix64(experiment_seed) ^ fnv1a64(node_name));
}

}  // namespace somasim
