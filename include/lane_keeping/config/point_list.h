#pragma once
/// An immutable list of [x, y] points (a lane's waypoints) that the copies of a configuration share.
/// A lane from a map has 10^5 points (1.6 MB), and one run copies its configuration a dozen times (the
/// nodes' and stages' own copies, the validity checks, the lane cache's key); as a vector each copy cost
/// a megabyte of fresh pages, together most of a short run's start-up (issue 18). A copy here shares the
/// points; a change replaces the whole list, so no copy ever sees another's change (value semantics).
#include <array>
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <utility>
#include <vector>

namespace lane_keeping {

using Point2 = std::array<double, 2>;

class PointList {
 public:
  PointList() : points_(none()) {}
  PointList(std::initializer_list<Point2> points) : PointList(std::vector<Point2>(points)) {}
  PointList(std::vector<Point2> points)  // NOLINT(google-explicit-constructor): a list of points is one
      : points_(std::make_shared<const std::vector<Point2>>(std::move(points))) {}

  const std::vector<Point2>& points() const { return *points_; }
  operator const std::vector<Point2>&() const { return *points_; }  // NOLINT: read as the vector it holds

  std::size_t size() const { return points_->size(); }
  bool empty() const { return points_->empty(); }
  const Point2& operator[](std::size_t i) const { return (*points_)[i]; }
  std::vector<Point2>::const_iterator begin() const { return points_->begin(); }
  std::vector<Point2>::const_iterator end() const { return points_->end(); }

  /// The same points: shared (a copy; O(1)), or equal one by one.
  friend bool operator==(const PointList& a, const PointList& b) {
    return a.points_ == b.points_ || *a.points_ == *b.points_;
  }
  friend bool operator!=(const PointList& a, const PointList& b) { return !(a == b); }

 private:
  static const std::shared_ptr<const std::vector<Point2>>& none() {
    static const auto empty = std::make_shared<const std::vector<Point2>>();
    return empty;
  }
  std::shared_ptr<const std::vector<Point2>> points_;
};

}  // namespace lane_keeping
