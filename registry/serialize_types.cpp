// Archive layout of each member type of the per-shape results (registry/types.h) and of the
// types that are not lists of members. Changing a layout here, or a result's Members(),
// requires bumping kArchiveVersion so that old cache entries become misses.
#include "registry/serialize.h"

namespace symembed {
void WriteMember(ArchiveWriter& out, bool value) { out.Bool(value); }
void WriteMember(ArchiveWriter& out, int value) { out.I64(value); }
void WriteMember(ArchiveWriter& out, double value) { out.F64(value); }
void WriteMember(ArchiveWriter& out, const std::string& value) { out.String(value); }
void WriteMember(ArchiveWriter& out, const std::vector<int>& values) { out.Ints(values); }
void WriteMember(ArchiveWriter& out, const std::vector<double>& values) { out.Doubles(values); }
void WriteMember(ArchiveWriter& out, const Eigen::MatrixX3d& M) { out.Matrix(M); }
void WriteMember(ArchiveWriter& out, const Eigen::VectorXd& v) { out.Matrix(v); }
void WriteMember(ArchiveWriter& out, const Eigen::Vector3d& v) { out.Matrix(v); }

void ReadMember(ArchiveReader& in, bool* value) { *value = in.Bool(); }
void ReadMember(ArchiveReader& in, int* value) { *value = static_cast<int>(in.I64()); }
void ReadMember(ArchiveReader& in, double* value) { *value = in.F64(); }
void ReadMember(ArchiveReader& in, std::string* value) { *value = in.String(); }
void ReadMember(ArchiveReader& in, std::vector<int>* values) { *values = in.Ints(); }
void ReadMember(ArchiveReader& in, std::vector<double>* values) { *values = in.Doubles(); }
void ReadMember(ArchiveReader& in, Eigen::MatrixX3d* M) {
  const Eigen::MatrixXd N = in.Matrix();
  if (N.cols() != 3 && N.size() != 0) throw ArchiveError("expected an N x 3 matrix");
  *M = N.size() == 0 ? Eigen::MatrixX3d() : Eigen::MatrixX3d(N);
}

void ReadMember(ArchiveReader& in, Eigen::VectorXd* v) {
  const Eigen::MatrixXd M = in.Matrix();
  if (M.cols() > 1) throw ArchiveError("expected a vector");
  *v = M.size() ? Eigen::VectorXd(M) : Eigen::VectorXd();
}

void ReadMember(ArchiveReader& in, Eigen::Vector3d* v) {
  const Eigen::MatrixXd M = in.Matrix();
  if (M.rows() != 3 || M.cols() != 1) throw ArchiveError("expected a 3-vector");
  *v = M;
}

void Write(ArchiveWriter& out, const Report& report) {
  out.U64(report.size());
  for (const auto& [name, value] : report) {
    out.String(name);
    out.F64(value);
  }
}

void Read(ArchiveReader& in, Report* report) {
  const uint64_t n = in.U64();
  report->clear();
  for (uint64_t i = 0; i < n; ++i) {
    std::string name = in.String();
    report->emplace_back(std::move(name), in.F64());
  }
}

void Write(ArchiveWriter& out, const Surface& surface) {
  out.Matrix(surface.V);
  out.IntMatrix(surface.F);
}

void Read(ArchiveReader& in, Surface* surface) {
  ReadMember(in, &surface->V);
  Eigen::MatrixXi F = in.IntMatrix();
  if (F.cols() != 3 && F.size() != 0) throw ArchiveError("expected an F x 3 face matrix");
  surface->F = F.size() == 0 ? Eigen::MatrixX3i() : Eigen::MatrixX3i(F);
}

void Write(ArchiveWriter& out, const Eigen::MatrixXd& M) { out.Matrix(M); }
void Read(ArchiveReader& in, Eigen::MatrixXd* M) { *M = in.Matrix(); }

void Write(ArchiveWriter& out, const LaplaceBasis& basis) {
  out.Matrix(basis.evals);
  out.Matrix(basis.evecs);
  out.Matrix(basis.mass);
}

void Read(ArchiveReader& in, LaplaceBasis* basis) {
  const Eigen::MatrixXd evals = in.Matrix(), evecs = in.Matrix(), mass = in.Matrix();
  if (evals.cols() != 1 || mass.cols() != 1 || evecs.cols() != evals.rows() ||
      evecs.rows() != mass.rows()) {
    throw ArchiveError("inconsistent Laplace-Beltrami basis");
  }
  basis->evals = evals.col(0);
  basis->evecs = evecs;
  basis->mass = mass.col(0);
}

}  // namespace symembed
