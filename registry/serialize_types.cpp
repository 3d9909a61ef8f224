// Archive layout of the per-shape results (registry/types.h). Changing a layout here requires
// bumping kArchiveVersion so that old cache entries become misses.
#include "registry/serialize.h"

namespace symembed {
namespace {

Eigen::MatrixX3d ReadN3(ArchiveReader& in) {
  Eigen::MatrixXd M = in.Matrix();
  if (M.cols() != 3 && M.size() != 0) throw ArchiveError("expected an N x 3 matrix");
  return M.size() == 0 ? Eigen::MatrixX3d() : Eigen::MatrixX3d(M);
}

}  // namespace

void Write(ArchiveWriter& out, const StageStatus& status) {
  out.Bool(status.converged);
  out.I64(status.iterations);
  out.F64(status.residual);
  out.String(status.message);
}

void Read(ArchiveReader& in, StageStatus* status) {
  status->converged = in.Bool();
  status->iterations = static_cast<int>(in.I64());
  status->residual = in.F64();
  status->message = in.String();
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
  surface->V = ReadN3(in);
  Eigen::MatrixXi F = in.IntMatrix();
  if (F.cols() != 3 && F.size() != 0) throw ArchiveError("expected an F x 3 face matrix");
  surface->F = F.size() == 0 ? Eigen::MatrixX3i() : Eigen::MatrixX3i(F);
}

void Write(ArchiveWriter& out, const PreprocessResult& result) {
  Write(out, result.surface);
  out.Ints(result.input_ids);
  out.F64(result.scale);
  Write(out, result.report);
  Write(out, result.status);
}

void Read(ArchiveReader& in, PreprocessResult* result) {
  Read(in, &result->surface);
  result->input_ids = in.Ints();
  result->scale = in.F64();
  Read(in, &result->report);
  Read(in, &result->status);
}

void Write(ArchiveWriter& out, const SamplingResult& result) {
  out.Ints(result.samples);
  out.F64(result.coverage_radius);
  Write(out, result.status);
}

void Read(ArchiveReader& in, SamplingResult* result) {
  result->samples = in.Ints();
  result->coverage_radius = in.F64();
  Read(in, &result->status);
}

void Write(ArchiveWriter& out, const EmbeddingResult& result) {
  out.Matrix(result.Y);
  out.F64(result.normalized_stress);
  out.I64(result.reflection);
  out.Doubles(result.stress_history);
  Write(out, result.status);
}

void Read(ArchiveReader& in, EmbeddingResult* result) {
  result->Y = in.Matrix();
  result->normalized_stress = in.F64();
  result->reflection = static_cast<int>(in.I64());
  result->stress_history = in.Doubles();
  Read(in, &result->status);
}

void Write(ArchiveWriter& out, const SymmetryResult& result) {
  out.Matrix(result.normal);
  out.F64(result.offset);
  out.Ints(result.sigma);
  out.Matrix(result.confidence);
  out.F64(result.score);
  out.F64(result.tie_displacement);
  Write(out, result.status);
}

void Read(ArchiveReader& in, SymmetryResult* result) {
  Eigen::MatrixXd normal = in.Matrix();
  if (normal.rows() != 3 || normal.cols() != 1) throw ArchiveError("expected a 3-vector");
  result->normal = normal;
  result->offset = in.F64();
  result->sigma = in.Ints();
  Eigen::MatrixXd confidence = in.Matrix();
  if (confidence.cols() > 1) throw ArchiveError("expected a vector");
  result->confidence = confidence.size() ? Eigen::VectorXd(confidence) : Eigen::VectorXd();
  result->score = in.F64();
  result->tie_displacement = in.F64();
  Read(in, &result->status);
}

void Write(ArchiveWriter& out, const SymmetrizeResult& result) {
  out.Matrix(result.Y);
  out.F64(result.asymmetry_before);
  out.F64(result.asymmetry_after);
  Write(out, result.status);
}

void Read(ArchiveReader& in, SymmetrizeResult* result) {
  result->Y = ReadN3(in);
  result->asymmetry_before = in.F64();
  result->asymmetry_after = in.F64();
  Read(in, &result->status);
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
