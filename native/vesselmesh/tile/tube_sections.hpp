#pragma once
// A tube's square cross-sections in a row (frames/Section, corners at scale × radius): where two
// consecutive ones fold (one's square reaching across the other's plane), the longest chains of them
// that do not, and where the inner ones stand so that the Loop limit surface passes through their
// centres. The base mesh builds its tubes from these and finds the bends it tiles as corners with them.

#include <cstddef>
#include <vector>

#include "vesselmesh/frames/frames.hpp"

namespace vesselmesh {

/// Kept sections are at most this many of the sampled sections apart (fold_free_chains, drop_folds).
constexpr std::size_t kFoldSkip = 64;

/// Whether the squares of consecutive sections a and b (normals along the travel, corners within
/// reach_a and reach_b of their centres) reach across each other's planes: b's behind a's, or a's
/// ahead of b's.
bool sections_cross(const Section& a, double reach_a, const Section& b, double reach_b);
/// The same with the corners at scale × radius.
bool sections_cross(const Section& a, const Section& b, double scale);

/// The largest distance of a section's corners from its centre: scale × r, pushed out by the lean of
/// its normal against `axis`, the direction the tube really runs (capped at twice, a 60° lean).
double corner_reach(const Section& s, const Vec3& axis, double scale);

/// For each section, the most sections a chain from the first to it keeps, no two kept in a row
/// crossing and none more than kFoldSkip apart; 0 where no chain gets. `from` receives each section's
/// predecessor in its chain.
std::vector<int> fold_free_chains(const std::vector<Section>& sections, double scale,
                                  std::vector<std::size_t>& from);

/// Keeps the most sections such that no two kept in a row cross; the end sections stay.
void drop_folds(std::vector<Section>& sections, double scale);

/// When only the two end sections are left and even these cross, turns the free ones (terminal ends) so
/// that they cannot.
void unfold_ends(std::vector<Section>& sections, bool free_front, bool free_back, double scale);

/// Moves the inner sections' centres so that the Loop limit surface passes through where they were;
/// `axis`: per section, the direction the tube really runs there; `ring`: the last section repeats the
/// first.
void place_for_limit(std::vector<Section>& sections, const std::vector<Vec3>& axis, bool ring, double scale);

}  // namespace vesselmesh
