#include "run.hpp"

int main(int argc, char** argv) { return sphstab::cli::run(argc, argv); }
