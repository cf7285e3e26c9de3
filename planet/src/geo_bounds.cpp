// thalassa — geodetic bounding regions (geo_bounds.hpp).
#include "thalassa/planet/geo_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace thalassa {
namespace {

// Longitude in [-180, 180).
double normalise(double lon) {
  double r = std::fmod(lon + 180.0, 360.0);
  if (r < 0.0) r += 360.0;
  return r - 180.0;
}

// Eastward distance from a to b, degrees, [0, 360).
double east_of(double a, double b) {
  double d = std::fmod(b - a, 360.0);
  if (d < 0.0) d += 360.0;
  return d;
}

}  // namespace

double GeoBounds::longitude_span() const {
  if (full_longitude()) return 360.0;
  return west <= east ? east - west : 360.0 - (west - east);
}

bool GeoBounds::contains(double lat, double lon) const {
  if (empty() || !(lat >= south && lat <= north)) return false;
  if (full_longitude()) return true;
  return east_of(west, lon) <= longitude_span();
}

bool GeoBounds::intersects(const GeoBounds& o) const {
  if (empty() || o.empty()) return false;
  if (south > o.north || o.south > north) return false;
  if (full_longitude() || o.full_longitude()) return true;
  // Two arcs on a circle meet when one's start lies in the other.
  return east_of(west, o.west) <= longitude_span() || east_of(o.west, west) <= o.longitude_span();
}

GeoBounds GeoBounds::expanded(double metres, double a, double f) const {
  if (empty()) return *this;
  constexpr double kDegrees = 180.0 / std::numbers::pi;
  const double e2 = f * (2.0 - f);
  const double lat_pad = metres / (a * (1.0 - e2)) * kDegrees;
  GeoBounds r = *this;
  r.south = std::max(-90.0, south - lat_pad);
  r.north = std::min(90.0, north + lat_pad);
  const double farthest = std::max(std::abs(r.south), std::abs(r.north));
  const double parallel = a * std::cos(farthest / kDegrees);
  if (r.south <= -90.0 || r.north >= 90.0 || !(parallel > 0.0)) {
    r.west = -180.0;
    r.east = 180.0;
    return r;
  }
  const double lon_pad = metres / parallel * kDegrees;
  if (full_longitude() || longitude_span() + 2.0 * lon_pad >= 360.0) {
    r.west = -180.0;
    r.east = 180.0;
  } else {
    r.west = normalise(west - lon_pad);
    r.east = normalise(east + lon_pad);
    if (r.east == -180.0) r.east = 180.0;
  }
  return r;
}

GeoBounds GeoBounds::from_arcs(double south, double north,
                               const std::vector<std::pair<double, double>>& arcs) {
  GeoBounds r;
  r.south = south;
  r.north = north;
  if (arcs.empty()) return GeoBounds{};
  // Sort by start in [-180, 180), merge, and find the largest gap between merged arcs.
  std::vector<std::pair<double, double>>
      s;  // [start, end] with end = start + length (may pass 180)
  for (const auto& [start, length] : arcs) {
    if (length >= 360.0) {
      r.west = -180.0;
      r.east = 180.0;
      return r;
    }
    const double st = normalise(start);
    s.emplace_back(st, st + std::max(0.0, length));
  }
  std::sort(s.begin(), s.end());
  std::vector<std::pair<double, double>> merged;
  for (const auto& arc : s) {
    if (!merged.empty() && arc.first <= merged.back().second) {
      merged.back().second = std::max(merged.back().second, arc.second);
    } else {
      merged.push_back(arc);
    }
  }
  // An arc reaching past 180 may cover the starts of the first arcs (wrap-around).
  while (merged.size() > 1 && merged.back().second - 360.0 >= merged.front().first) {
    merged.back().second = std::max(merged.back().second, merged.front().second + 360.0);
    merged.erase(merged.begin());
  }
  if (merged.back().second - merged.back().first >= 360.0) {
    r.west = -180.0;
    r.east = 180.0;
    return r;
  }
  // Gaps: after each merged arc up to the next's start (the last wraps to the first + 360).
  double best_gap = -1.0;
  std::size_t best = 0;
  for (std::size_t i = 0; i < merged.size(); ++i) {
    const double next = i + 1 < merged.size() ? merged[i + 1].first : merged[0].first + 360.0;
    const double gap = next - merged[i].second;
    if (gap > best_gap) {
      best_gap = gap;
      best = i;
    }
  }
  if (best_gap <= 0.0) {
    r.west = -180.0;
    r.east = 180.0;
    return r;
  }
  // The region starts after the largest gap and ends where it begins.
  const std::size_t after = (best + 1) % merged.size();
  r.west = normalise(merged[after].first);
  r.east = normalise(merged[best].second);
  if (r.east == -180.0 && r.west != -180.0) r.east = 180.0;
  return r;
}

}  // namespace thalassa
