// libFuzzer target: the run-file reader (common/run_config_resolve.h) on the
// shipped configs folder (BSG_CONFIGS_DIR). Any input resolves to a valid
// configuration or gives a ConfigError.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "common/config_error.h"
#include "common/run_config_resolve.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/bsg_run_file_fuzzer_" + std::to_string(::getpid()) + ".yaml";
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
  bsg::RunConfigRequest request;
  request.configs_dir = BSG_CONFIGS_DIR;
  request.run_file = path;
  try {
    const bsg::ResolvedRunConfig resolved = bsg::resolve_run_config(request);
    if (resolved.config.max_ep_len > resolved.config.steps_per_epoch) __builtin_trap();
  } catch (const bsg::ConfigError&) {
  }
  return 0;
}
