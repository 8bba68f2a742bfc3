#pragma once
// The backend a Session hands out: it forwards every call to the model's backend, which Session::set
// may replace by one built with a changed key and given the state the old one had, so what holds the
// session's backend (the run loop, a model's run front end) keeps a valid reference across a change.
#include "common/simulation/simulation_backend.hpp"
#include "common/simulation/simulation_state.hpp"

#include <memory>
#include <utility>

namespace physarum {

class LiveBackend final : public SimulationBackend {
 public:
  explicit LiveBackend(std::unique_ptr<SimulationBackend> inner) : inner_(std::move(inner)) {}

  // The backend now, and its replacement (continuing from the current one's state).
  SimulationBackend& inner() { return *inner_; }
  const SimulationBackend& inner() const { return *inner_; }
  void replace(std::unique_ptr<SimulationBackend> next) {
    next->restore_state(inner_->save_state());
    inner_ = std::move(next);
  }

  void step() override { inner_->step(); }
  void run(long long steps) override { inner_->run(steps); }
  void finish() override { inner_->finish(); }
  int layer_count() const override { return inner_->layer_count(); }
  int dynamic_layer_count() const override { return inner_->dynamic_layer_count(); }
  int add_static_layer(const IntrinsicVertexData<double>& values) override { return inner_->add_static_layer(values); }
  IntrinsicVertexData<double> field_values(int layer) const override { return inner_->field_values(layer); }
  void set_field(const IntrinsicVertexData<double>& values, int layer) override { inner_->set_field(values, layer); }
  void fill_field(double value, int layer) override { inner_->fill_field(value, layer); }
  FieldStatistics field_statistics(double U, int layer) const override { return inner_->field_statistics(U, layer); }
  double time() const override { return inner_->time(); }
  long long steps_taken() const override { return inner_->steps_taken(); }
  std::vector<int> agent_faces() const override { return inner_->agent_faces(); }
  SimulationCounters counters() const override { return inner_->counters(); }
  SimulationState save_state() const override { return inner_->save_state(); }
  void restore_state(const SimulationState& state) override { inner_->restore_state(state); }
  std::string backend_name() const override { return inner_->backend_name(); }
  std::string device_name() const override { return inner_->device_name(); }

 private:
  std::unique_ptr<SimulationBackend> inner_;
};

}  // namespace physarum
