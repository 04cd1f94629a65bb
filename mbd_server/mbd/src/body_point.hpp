#pragma once
// A material point of a body, or a fixed point of the ground, as seen from the model's full
// coordinate vector q: the building block of joints and spring-dampers (internal).

#include <Eigen/Dense>

#include <vector>

#include "body.hpp"
#include "fsi/mbd/matrix_sink.hpp"

namespace fsi::mbd::detail {

// A D x n matrix (n = coordinate count) by its non-zero columns: the index into q and the
// column. An index may repeat; its columns add. Points depend on a few coordinates only, so
// joints and springs combine these instead of D x n dense matrices (D = 2: planar points,
// SparseColumns; D = 3: spatial points, SpatialColumns).
template <int D>
struct PointColumns {
  using Column = Eigen::Matrix<double, D, 1>;
  std::vector<int> index;
  std::vector<Column> column;

  void add(int i, const Column& c) {
    index.push_back(i);
    column.push_back(c);
  }
  void append(const PointColumns& other, double sign) {
    for (std::size_t k = 0; k < other.index.size(); ++k)
      add(other.index[k], sign * other.column[k]);
  }
  // Adds the row w^T (this) at `row` of the sink.
  void add_row(MatrixSink& sink, int row, const Column& w) const {
    for (std::size_t k = 0; k < index.size(); ++k)
      sink.add(row, index[k], w.dot(column[k]));
  }
  // Adds scale * (this)^T mixing other (n x n).
  void add_transpose_product(MatrixSink& sink, const Eigen::Matrix<double, D, D>& mixing,
                             const PointColumns& other, double scale = 1.0) const {
    for (std::size_t i = 0; i < index.size(); ++i) {
      const Eigen::Matrix<double, 1, D> left = scale * column[i].transpose() * mixing;
      for (std::size_t k = 0; k < other.index.size(); ++k)
        sink.add(index[i], other.index[k], left * other.column[k]);
    }
  }
  // Adds (this)^T f to a vector of size n.
  void add_transpose_times(const Column& f, Eigen::VectorXd& out) const {
    for (std::size_t k = 0; k < index.size(); ++k)
      out(index[k]) += column[k].dot(f);
  }
};

using SparseColumns = PointColumns<2>;
using SpatialColumns = PointColumns<3>;

class BodyPoint {
 public:
  // body == nullptr: a ground point at the world position `local`.
  BodyPoint(const Body* body, int offset, const Eigen::Vector2d& local)
      : body_(body), offset_(offset), local_(local) {}

  bool on_ground() const { return body_ == nullptr; }
  Eigen::Vector2d position(const Eigen::VectorXd& q) const;
  Eigen::Vector2d velocity(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  // Adds sign * dr/dq (2 x n, its non-zero columns) to `jacobian`.
  void add_jacobian(const Eigen::VectorXd& q, double sign, SparseColumns& jacobian) const;
  // Adds sign * d/dq [(dr/dq) v] (2 x n, its non-zero columns) to `jacobian`.
  void add_velocity_jacobian(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double sign,
                             SparseColumns& jacobian) const;
  // The acceleration-free part of d^2r/dt^2: d/dq [(dr/dq) v] v.
  Eigen::Vector2d acceleration_remainder(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  // Adds d/dq [(dr/dq)^T f] at constant f (n x n) into `derivative`.
  void add_load_derivative(const Eigen::VectorXd& q, const Eigen::Vector2d& force,
                           MatrixSink& derivative) const;
  // Adds the generalised force (dr/dq)^T f of a world-frame force f (size n).
  void add_load(const Eigen::VectorXd& q, const Eigen::Vector2d& force,
                Eigen::VectorXd& generalised_force) const;

 private:
  auto block(const Eigen::VectorXd& x) const {
    return x.segment(offset_, body_->coordinate_count());
  }

  const Body* body_;
  int offset_;
  Eigen::Vector2d local_;
};

}  // namespace fsi::mbd::detail
