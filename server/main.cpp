// tourmap: the service's single executable.
#include "cli.hpp"

int main(int argc, char** argv) { return tourmap::server::run_cli(argc, argv); }
