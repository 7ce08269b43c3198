#include "run.hpp"
#include "sphstab/core/threads.hpp"

int main(int argc, char** argv) {
  sphstab::set_program_wait_policy(argv);  // before any thread waits (core/threads.hpp: why a re-execution)
  return sphstab::cli::run(argc, argv);
}
