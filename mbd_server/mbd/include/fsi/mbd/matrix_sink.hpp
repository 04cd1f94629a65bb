#pragma once
// Where elements put the entries of a derivative matrix (dF/dq, dF/dv, G, d(G^T lambda)/dq):
// each entry is ADDED at a global (row, column), so an element writes only its non-zeros and the
// model assembles dense matrices for small systems and triplet lists (sparse matrices) for
// large ones from the same element code.

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <vector>

namespace fsi::mbd {

class MatrixSink {
 public:
  virtual ~MatrixSink() = default;

  // Adds `value` at (row, column). Exact zeros may be added: they keep a sparsity pattern fixed.
  virtual void add(int row, int column, double value) = 0;

  // Adds scale * block with its top-left entry at (row, column).
  template <typename Derived>
  void add_block(int row, int column, const Eigen::MatrixBase<Derived>& block, double scale = 1.0) {
    for (Eigen::Index j = 0; j < block.cols(); ++j) {
      for (Eigen::Index i = 0; i < block.rows(); ++i)
        add(row + static_cast<int>(i), column + static_cast<int>(j), scale * block(i, j));
    }
  }
};

// Adds into a dense matrix (or a block of one).
class DenseMatrixSink final : public MatrixSink {
 public:
  explicit DenseMatrixSink(Eigen::Ref<Eigen::MatrixXd> matrix) : matrix_(matrix) {}
  void add(int row, int column, double value) override { matrix_(row, column) += value; }

 private:
  Eigen::Ref<Eigen::MatrixXd> matrix_;
};

// Collects triplets; to_matrix() sums repeated entries into a compressed sparse matrix whose
// pattern holds every added position (explicit zeros included).
class TripletSink final : public MatrixSink {
 public:
  void add(int row, int column, double value) override {
    triplets_.emplace_back(row, column, value);
  }
  void clear() { triplets_.clear(); }
  const std::vector<Eigen::Triplet<double>>& triplets() const { return triplets_; }
  void to_matrix(int rows, int columns, Eigen::SparseMatrix<double>& matrix) const {
    matrix.resize(rows, columns);
    matrix.setFromTriplets(triplets_.begin(), triplets_.end());
  }

 private:
  std::vector<Eigen::Triplet<double>> triplets_;
};

// Forwards scale * value to (row_offset + row, column_offset + column) of another sink: a body
// writes its block in its own coordinates.
class OffsetSink final : public MatrixSink {
 public:
  OffsetSink(MatrixSink& target, int row_offset, int column_offset, double scale = 1.0)
      : target_(target), row_offset_(row_offset), column_offset_(column_offset), scale_(scale) {}
  void add(int row, int column, double value) override {
    target_.add(row_offset_ + row, column_offset_ + column, scale_ * value);
  }

 private:
  MatrixSink& target_;
  int row_offset_;
  int column_offset_;
  double scale_;
};

}  // namespace fsi::mbd
