# What somasim's public targets need, found for a project that uses the package (installed or
# from the build tree): included by both package config files.
include(CMakeFindDependencyMacro)
find_dependency(Eigen3 3.3 NO_MODULE)
find_dependency(spdlog)
find_dependency(fmt)
find_dependency(nlohmann_json 3)
find_dependency(OpenCV COMPONENTS core imgproc imgcodecs)
# somasim::body_schema spreads particles over MPI ranks (its ParticleRanks holds an MPI_Comm).
set(MPI_CXX_SKIP_MPICXX ON)
find_dependency(MPI COMPONENTS CXX)
