// The registry of environment ids (design.md; OpenSpiel-style function-local
// static map): every id names a description (env_description.h), built by the
// one builder (env_builder.h). The 16 standard ids come from
// standard_descriptions.h; a variant set is one more list of descriptions.
// make(), describe() and registered_ids() of env.h read it.
#pragma once

#include <map>
#include <string>

#include "envs/description/env_description.h"

namespace bsg::envs {

// Every registered id, built once on first use.
const std::map<std::string, EnvDescription>& registry();

// The description registered as `id`; throws std::invalid_argument listing
// the valid ids.
const EnvDescription& find_description(const std::string& id);

}  // namespace bsg::envs
