#include "algos/core/network_checkpoint.h"

#include "algos/core/adam_state.h"

namespace bsg::algos {

void save_value_function(const ValueFunction& value, BinaryWriter& writer) {
  writer.write_vector(value.net().parameters());
  save_adam_state(value.optimizer(), writer);
}

void load_value_function(ValueFunction& value, BinaryReader& reader, const std::string& name) {
  const Eigen::Index size = value.net().num_parameters();
  value.net().set_parameters(reader.read_vector(name + " parameters", size));
  load_adam_state(value.optimizer(), reader, name);
}

void save_normalizer(const RunningMeanStd& normalizer, BinaryWriter& writer) {
  writer.write_vector(normalizer.mean());
  writer.write_vector(normalizer.std());
  writer.write_f64(normalizer.count());
}

void load_normalizer(RunningMeanStd& normalizer, BinaryReader& reader, const std::string& name) {
  const Eigen::VectorXd mean = reader.read_vector(name + " mean", normalizer.dimension());
  const Eigen::VectorXd std = reader.read_vector(name + " std", normalizer.dimension());
  const double count = reader.read_f64(name + " count");
  normalizer.set_state(mean, std, count);
}

}  // namespace bsg::algos
