// evms: event-based mean-shift clustering and tracking (host/cli/main.cpp holds the program).
#include "host/cli/commands.h"

int main(int argc, char** argv) { return evms::cli::run_evms(argc, argv); }
