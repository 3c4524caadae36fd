// The `bsg` program's subcommands. Each one registers itself on the top-level
// app and, when it is the one chosen, stores its action in `run`; main() calls
// that action after parsing so that every error is reported the same way.
#pragma once

#include <functional>

namespace CLI {
class App;
}

namespace bsg::cli {

// Returns the process exit code.
using Action = std::function<int()>;

}  // namespace bsg::cli
