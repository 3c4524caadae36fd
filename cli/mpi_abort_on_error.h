// Runs a command's body so that an error on any MPI rank ends the whole job
// with a message instead of leaving the other ranks waiting in a collective:
// with more than one rank, the failing rank prints the error (naming its
// rank) and calls MPI_Abort. With one process the exception propagates to
// main(), which prints it and exits with code 1.
#pragma once

#include <exception>
#include <iostream>

#include "common/message_text.h"
#include "common/mpi_context.h"

namespace bsg::cli {

template <typename Body>
int run_or_abort_job(const MpiContext& mpi, Body&& body) {
  if (mpi.size() <= 1) return body();
  try {
    return body();
  } catch (const std::exception& e) {
    std::cerr << "bsg: error on MPI rank " << mpi.rank() << " of " << mpi.size() << ": " << printable_message(e.what())
              << "\nbsg: aborting all ranks" << std::endl;
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }
}

}  // namespace bsg::cli
