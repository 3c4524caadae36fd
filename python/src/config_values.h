// bsg.train's configuration from Python values: a dict in place of a run file, keywords in place
// of `--set key=value`, each value read as its YAML equivalent (True/False as true/false, ints and
// floats as Python writes them, str as quoted YAML text, lists as sequences, dicts as mappings,
// None as null), so that the run's config.yaml is the one `bsg train` writes from the same values.
#pragma once

#include <pybind11/pybind11.h>

#include <functional>
#include <string>
#include <vector>

#include "common/config_entries.h"

namespace bsg::python {

// The entries of `values` (a dict of key -> value, named `what` in messages); origin(key) names
// each entry in messages, e.g. "config['epochs']" or "bsg.train(epochs=...)". TypeError for a
// non-str key or a value of another type; ConfigError for a key that is not in the schema.
std::vector<ConfigEntry> config_entries_from_dict(pybind11::handle values, const std::string& what,
                                                  const std::function<std::string(const std::string&)>& origin);

}  // namespace bsg::python
