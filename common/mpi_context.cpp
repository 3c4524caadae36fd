#include "common/mpi_context.h"

#include <climits>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace bsg {
namespace {

bool mpi_is_initialised() {
  int initialised = 0;
  int finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  return initialised != 0 && finalised == 0;
}

int checked_count(std::size_t count, const char* where) {
  if (count > static_cast<std::size_t>(INT_MAX)) {
    throw std::length_error(std::string(where) + ": " + std::to_string(count) +
                            " values exceed MPI's int count");
  }
  return static_cast<int>(count);
}

}  // namespace

MpiContext::MpiContext(MPI_Comm communicator, int rank, int size, bool uses_mpi)
    : communicator_(communicator), rank_(rank), size_(size), uses_mpi_(uses_mpi) {}

MpiContext MpiContext::world() {
  if (!mpi_is_initialised()) {
    throw std::logic_error("MpiContext::world: MPI is not initialised (create an MpiSession first)");
  }
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return MpiContext(MPI_COMM_WORLD, rank, size, true);
}

MpiContext MpiContext::single_process() { return MpiContext(MPI_COMM_NULL, 0, 1, false); }

void MpiContext::sum_in_place(double* values, std::size_t count) const {
  if (!collective_needed() || count == 0) return;
  MPI_Allreduce(MPI_IN_PLACE, values, checked_count(count, "MpiContext::sum_in_place"),
                MPI_DOUBLE, MPI_SUM, communicator_);
}

void MpiContext::sum_in_place(Eigen::Ref<Eigen::VectorXd> values) const {
  sum_in_place(values.data(), static_cast<std::size_t>(values.size()));
}

void MpiContext::average_in_place(double* values, std::size_t count) const {
  if (!collective_needed()) return;
  sum_in_place(values, count);
  const double inverse_size = 1.0 / size_;
  for (std::size_t i = 0; i < count; ++i) values[i] *= inverse_size;
}

void MpiContext::average_in_place(Eigen::Ref<Eigen::VectorXd> values) const {
  average_in_place(values.data(), static_cast<std::size_t>(values.size()));
}

double MpiContext::average(double value) const {
  average_in_place(&value, 1);
  return value;
}

double MpiContext::sum(double value) const {
  sum_in_place(&value, 1);
  return value;
}

long long MpiContext::sum(long long value) const {
  if (!collective_needed()) return value;
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_LONG_LONG, MPI_SUM, communicator_);
  return value;
}

double MpiContext::min(double value) const {
  if (!collective_needed()) return value;
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MIN, communicator_);
  return value;
}

double MpiContext::max(double value) const {
  if (!collective_needed()) return value;
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MAX, communicator_);
  return value;
}

void MpiContext::broadcast_from_root(double* values, std::size_t count) const {
  if (!collective_needed() || count == 0) return;
  MPI_Bcast(values, checked_count(count, "MpiContext::broadcast_from_root"), MPI_DOUBLE, 0,
            communicator_);
}

void MpiContext::broadcast_from_root(Eigen::Ref<Eigen::VectorXd> values) const {
  broadcast_from_root(values.data(), static_cast<std::size_t>(values.size()));
}

std::vector<double> MpiContext::gather_to_root(const std::vector<double>& local_values) const {
  if (!collective_needed()) return local_values;
  const int local_count = checked_count(local_values.size(), "MpiContext::gather_to_root");
  std::vector<int> counts(is_root() ? size_ : 0);
  MPI_Gather(&local_count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, communicator_);
  std::vector<int> offsets(counts.size(), 0);
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = checked_count(total, "MpiContext::gather_to_root");
    total += static_cast<std::size_t>(counts[r]);
  }
  std::vector<double> gathered(total);
  MPI_Gatherv(local_values.data(), local_count, MPI_DOUBLE, gathered.data(), counts.data(),
              offsets.data(), MPI_DOUBLE, 0, communicator_);
  return gathered;
}

MpiSession::MpiSession(int& argc, char**& argv, Mode mode) { initialise(&argc, &argv, mode); }

MpiSession::MpiSession(Mode mode) { initialise(nullptr, nullptr, mode); }

void MpiSession::initialise(int* argc, char*** argv, Mode mode) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (initialised != 0) return;  // someone else owns MPI (e.g. a test main)
  if (mode == Mode::when_launched && !launched_by_mpi_launcher()) return;
  if (MPI_Init(argc, argv) != MPI_SUCCESS) {
    throw std::runtime_error("MpiSession: MPI_Init failed");
  }
  owns_mpi_ = true;
}

MpiSession::~MpiSession() {
  if (owns_mpi_ && mpi_is_initialised()) MPI_Finalize();
}

MpiContext MpiSession::context() const {
  return mpi_is_initialised() ? MpiContext::world() : MpiContext::single_process();
}

bool MpiSession::launched_by_mpi_launcher() {
  for (const char* variable :
       {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(variable) != nullptr) return true;
  }
  return false;
}

}  // namespace bsg
