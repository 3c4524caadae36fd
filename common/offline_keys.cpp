// The rows of OfflineKeys (common/offline_keys.h) in the key table, after the
// off-policy rows. An offline algorithm's own key is a member of OfflineKeys
// and a row here applying to its algorithms.
#include "common/offline_keys.h"

#include <vector>

#include "common/config_key_rows.h"

namespace bsg::key_rows {

// clang-format off
std::vector<ConfigKeyRow> offline_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  using K = OfflineKeys;
  return {
    // --- offline (docs/datasets.md#offline-runs) ---
    text("dataset", field<&R::offline, &K::dataset>(), L::run,
         "offline: the HDF5 dataset (DSRL's layout, e.g. from bsg collect) the policy learns from; its env_id "
         "must be the run's", kOffline),
    integer("updates_per_epoch", field<&R::offline, &K::updates_per_epoch>(), L::algorithm, N::closed(1, kIntMax), kOffline,
            "offline: gradient steps per epoch, each on batch_size rows drawn uniformly with replacement"),
    integer("eval_every", field<&R::offline, &K::eval_every>(), L::algorithm, N::closed(1, kIntMax), kOffline,
            "offline: evaluate online (eval_episodes episodes) after every eval_every-th epoch and the last"),
  };
}
// clang-format on

}  // namespace bsg::key_rows
