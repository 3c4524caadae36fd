// The MPI wrapper. Every quantity that must agree across ranks goes through an
// MpiContext (docs/algorithms.md#across-mpi-ranks), so single-process and `mpirun -np N` runs share all code.
//
// Two classes:
//  - MpiSession: the RAII owner of MPI_Init/MPI_Finalize, created once by main().
//    It initialises MPI only when the process was started by an MPI launcher
//    (or when asked to always do so) and finalises only what it initialised.
//    A plain `./bsg` therefore never touches MPI (Open MPI 4.1's singleton init
//    does work here, as root too, but costs ~0.3 s and needs a working runtime).
//  - MpiContext: rank, size and the collectives. A single-process context makes
//    no MPI call at all; with one rank every collective is the identity.
//
// Collectives work in place on the caller's memory (MPI_IN_PLACE): no allocation
// per call.
#pragma once

// Only MPI's C interface is used: skip the deprecated C++ bindings.
#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1
#endif
#ifndef MPICH_SKIP_MPICXX
#define MPICH_SKIP_MPICXX 1
#endif
#include <mpi.h>

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace bsg {

class MpiContext {
 public:
  // The MPI_COMM_WORLD context; throws std::logic_error if MPI is not initialised.
  static MpiContext world();
  // One process and no MPI: rank 0 of 1, collectives are identities.
  static MpiContext single_process();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }

  // Arithmetic mean over ranks (allreduce-sum / R), in place.
  void average_in_place(double* values, std::size_t count) const;
  void average_in_place(Eigen::Ref<Eigen::VectorXd> values) const;
  double average(double value) const;

  // Sum, minimum and maximum over ranks.
  void sum_in_place(double* values, std::size_t count) const;
  void sum_in_place(Eigen::Ref<Eigen::VectorXd> values) const;
  double sum(double value) const;
  long long sum(long long value) const;
  double min(double value) const;
  double max(double value) const;

  // Every rank receives rank 0's values; the sizes must agree on all ranks.
  void broadcast_from_root(double* values, std::size_t count) const;
  void broadcast_from_root(Eigen::Ref<Eigen::VectorXd> values) const;

  // Rank 0 receives every rank's values concatenated in rank order; the other
  // ranks receive an empty vector. Local sizes may differ between ranks.
  std::vector<double> gather_to_root(const std::vector<double>& local_values) const;

 private:
  MpiContext(MPI_Comm communicator, int rank, int size, bool uses_mpi);
  bool collective_needed() const { return uses_mpi_ && size_ > 1; }

  MPI_Comm communicator_;
  int rank_;
  int size_;
  bool uses_mpi_;
};

class MpiSession {
 public:
  enum class Mode {
    // Initialise MPI only if an MPI launcher (mpirun/mpiexec, srun) started us.
    when_launched,
    // Always initialise (Open MPI singleton init without a launcher).
    always,
  };

  MpiSession(int& argc, char**& argv, Mode mode = Mode::when_launched);
  explicit MpiSession(Mode mode = Mode::when_launched);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  // The world context if MPI is initialised (by us or before us), else single-process.
  MpiContext context() const;
  // True if this object called MPI_Init and will call MPI_Finalize.
  bool owns_mpi() const { return owns_mpi_; }

  // True if the environment shows an MPI launcher (Open MPI, PMIx, MPICH/PMI).
  static bool launched_by_mpi_launcher();

 private:
  void initialise(int* argc, char*** argv, Mode mode);
  bool owns_mpi_ = false;
};

}  // namespace bsg
