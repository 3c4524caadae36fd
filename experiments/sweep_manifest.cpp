#include "experiments/sweep_manifest.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/config_scalar.h"
#include "common/csv_text.h"

namespace bsg::experiments {

namespace {
constexpr const char* kHeader = "env_id,alg,config,seed,run_dir";
}

void write_sweep_manifest(const std::filesystem::path& sweep_dir, const std::vector<GridRun>& runs) {
  std::string text = std::string(kHeader) + "\n";
  for (const GridRun& run : runs) {
    text += csv_field(run.env_id) + "," + std::string(to_string(run.alg)) + "," +
            csv_field(run.config_name) + "," + std::to_string(run.seed) + "," +
            csv_field(run.relative_dir().generic_string()) + "\n";
  }
  write_file_atomically(sweep_dir / kSweepManifestName, text);
}

std::vector<GridRun> read_sweep_manifest(const std::filesystem::path& sweep_dir) {
  const std::filesystem::path path = sweep_dir / kSweepManifestName;
  std::vector<GridRun> runs;
  std::ifstream in(path);
  if (!in) return runs;
  std::string line;
  int line_number = 0;
  auto fail = [&](const std::string& message) {
    throw std::runtime_error(path.string() + ":" + std::to_string(line_number) + ": " + message);
  };
  while (std::getline(in, line)) {
    ++line_number;
    if (line_number == 1) {
      if (line != kHeader) fail("expected the header '" + std::string(kHeader) + "'");
      continue;
    }
    if (line.empty()) continue;
    std::vector<std::string> fields;
    try {
      fields = parse_csv_fields(line);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
    if (fields.size() != 5) fail("expected 5 fields, found " + std::to_string(fields.size()));
    GridRun run;
    run.env_id = fields[0];
    const auto alg = std::find(kAlgorithmNames.begin(), kAlgorithmNames.end(), fields[1]);
    if (alg == kAlgorithmNames.end()) fail("unknown algorithm '" + fields[1] + "'");
    run.alg = static_cast<Algorithm>(alg - kAlgorithmNames.begin());
    run.config_name = fields[2];
    const std::optional<std::int64_t> seed = parse_config_integer(fields[3]);
    if (!seed) fail("seed '" + fields[3] + "' is not an integer");
    run.seed = *seed;
    runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace bsg::experiments
