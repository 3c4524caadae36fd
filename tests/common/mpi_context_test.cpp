// The MPI wrapper in a process started without mpirun: no MPI is needed and
// every collective is the identity.
#include "common/mpi_context.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace bsg {
namespace {

TEST(MpiContext, SingleProcessCollectivesAreIdentities) {
  const MpiContext mpi = MpiContext::single_process();
  EXPECT_EQ(mpi.rank(), 0);
  EXPECT_EQ(mpi.size(), 1);
  EXPECT_TRUE(mpi.is_root());
  Eigen::VectorXd values(3);
  values << 1.0, -2.0, 3.5;
  const Eigen::VectorXd before = values;
  mpi.average_in_place(values);
  EXPECT_EQ(values, before);
  mpi.sum_in_place(values);
  EXPECT_EQ(values, before);
  mpi.broadcast_from_root(values);
  EXPECT_EQ(values, before);
  EXPECT_EQ(mpi.average(2.5), 2.5);
  EXPECT_EQ(mpi.sum(2.5), 2.5);
  EXPECT_EQ(mpi.sum(7LL), 7LL);
  EXPECT_EQ(mpi.min(-1.0), -1.0);
  EXPECT_EQ(mpi.max(4.0), 4.0);
  EXPECT_EQ(mpi.gather_to_root({1.0, 2.0}), (std::vector<double>{1.0, 2.0}));
}

TEST(MpiSession, WithoutALauncherLeavesMpiAloneAndGivesASingleProcessContext) {
  if (MpiSession::launched_by_mpi_launcher()) GTEST_SKIP() << "running under an MPI launcher";
  const MpiSession session;
  EXPECT_FALSE(session.owns_mpi());
  int initialised = 1;
  MPI_Initialized(&initialised);
  EXPECT_EQ(initialised, 0);
  const MpiContext mpi = session.context();
  EXPECT_EQ(mpi.size(), 1);
  EXPECT_EQ(mpi.rank(), 0);
}

TEST(MpiContext, WorldWithoutMpiInitialisedIsALogicError) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (initialised != 0) GTEST_SKIP() << "MPI already initialised in this process";
  EXPECT_THROW(MpiContext::world(), std::logic_error);
}

}  // namespace
}  // namespace bsg
