// The rank group of a build without MPI (CLOSURELAB_WITH_MPI=OFF): always one rank.
#include <cstdlib>
#include <iostream>

#include "experiments/runner/rank_group.hpp"

namespace closurelab {

RankGroup::RankGroup() {
  const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
  if (size && std::atoi(size) > 1 && std::getenv("OMPI_COMM_WORLD_RANK") &&
      std::atoi(std::getenv("OMPI_COMM_WORLD_RANK")) == 0)
    std::cerr << "warning: started by mpirun, but this closurelab was built without MPI (CLOSURELAB_WITH_MPI=OFF): "
                 "every rank runs the whole matrix on its own\n";
}

RankGroup::~RankGroup() = default;

void RankGroup::serve(const std::function<std::optional<std::string>(int)>&,
                      const std::function<void(const std::string&, int)>&) const {}

void RankGroup::abort(int) const {}

void RankGroup::work(const std::function<std::string(const std::string&)>&) const {}

}  // namespace closurelab
