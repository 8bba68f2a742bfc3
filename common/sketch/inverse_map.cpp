#include "common/sketch/inverse_map.hpp"

#include "common/base/errors.hpp"
#include "common/sketch/median.hpp"

// Boost 1.74's pchip.hpp calls isnan unqualified: <math.h> declares it in the global namespace.
#include <math.h>

#include <boost/math/interpolators/pchip.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace physarum {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream s(line);
  std::string f;
  while (std::getline(s, f, ',')) fields.push_back(f);
  return fields;
}

// A monotone cubic through (log attribute, log rate): the pooled points, ascending in attribute.
double interpolate(const std::vector<double>& attribute, const std::vector<double>& rate, double at) {
  std::vector<double> x, y;
  for (size_t i = 0; i < attribute.size(); ++i) x.push_back(std::log(attribute[i])), y.push_back(std::log(rate[i]));
  if (x.size() == 2) {  // PCHIP needs four points; two are a straight line in log-log
    const double t = (std::log(at) - x[0]) / (x[1] - x[0]);
    return std::exp(y[0] + t * (y[1] - y[0]));
  }
  if (x.size() == 3) {  // ... and three a broken one
    const size_t k = std::log(at) <= x[1] ? 0 : 1;
    const double t = (std::log(at) - x[k]) / (x[k + 1] - x[k]);
    return std::exp(y[k] + t * (y[k + 1] - y[k]));
  }
  boost::math::interpolators::pchip<std::vector<double>> spline(std::move(x), std::move(y));
  return std::exp(spline(std::log(at)));
}

}  // namespace

std::vector<TrainingRun> read_training_runs(const std::string& csv, const std::string& where) {
  std::stringstream in(csv);
  std::string line;
  std::vector<std::string> header;
  std::vector<TrainingRun> runs;
  int line_number = 0;
  auto column = [&](const char* name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw InputError(where + ": no column '" + name + "' in the header");
    return static_cast<size_t>(it - header.begin());
  };
  size_t rate = 0, seed = 0, spots = 0, area = 0, spacing = 0, stripe_width = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> fields = split(line);
    if (header.empty()) {
      header = fields;
      rate = column("rate"), seed = column("seed"), spots = column("spots"), area = column("spot_area"),
      spacing = column("spacing");
      const auto width = std::find(header.begin(), header.end(), "stripe_width");
      stripe_width = width == header.end() ? header.size() : static_cast<size_t>(width - header.begin());
      continue;
    }
    auto number = [&](size_t c) {
      double x = std::nan("");
      if (c < fields.size() && !fields[c].empty()) {
        std::istringstream s(fields[c]);
        s >> x;
        if (s.fail()) x = std::nan("");
      }
      return x;
    };
    TrainingRun run;
    run.rate = number(rate);
    if (!(run.rate > 0.0) || !std::isfinite(run.rate))
      throw InputError(where + ":" + std::to_string(line_number) + ": rate '" + (rate < fields.size() ? fields[rate] : "") +
                       "' is not a number > 0");
    run.seed = static_cast<int>(number(seed));
    run.spots = static_cast<int>(number(spots));
    run.spot_area = number(area);
    run.spacing = number(spacing);
    run.stripe_width = stripe_width < fields.size() ? number(stripe_width) : 0.0;
    if ((run.spot_area > 0.0 && run.spacing > 0.0) || run.stripe_width > 0.0) runs.push_back(run);
  }
  if (header.empty()) throw InputError(where + ": no header line (rate,seed,steps,spots,spot_area,spacing)");
  return runs;
}

double RateMap::exponent() const {
  return std::log(attribute_.back() / attribute_.front()) / std::log(rate_.back() / rate_.front());
}

RateMap::RateMap(const std::vector<double>& rate, const std::vector<double>& attribute, const std::string& attribute_name)
    : name_(attribute_name) {
  std::map<double, std::vector<double>> by_rate;
  for (size_t i = 0; i < rate.size() && i < attribute.size(); ++i)
    if (rate[i] > 0.0 && attribute[i] > 0.0) by_rate[rate[i]].push_back(attribute[i]);
  if (by_rate.size() < 3)
    throw InputError("inverse map of the " + name_ + ": " + std::to_string(by_rate.size()) +
                     " distinct rates with a measured pattern; it needs three or more");
  // Ascending in rate; the attribute should fall. Pool adjacent violators (each block's value the
  // weighted mean of its medians, in logs; its rate their geometric mean) until it does.
  struct Block {
    double log_attribute, log_rate;
    int count;
  };
  std::vector<Block> blocks;
  for (const auto& [r, values] : by_rate) {
    blocks.push_back({std::log(median(values)), std::log(r), 1});
    while (blocks.size() > 1 && blocks[blocks.size() - 2].log_attribute <= blocks.back().log_attribute) {
      const Block b = blocks.back();
      blocks.pop_back();
      Block& a = blocks.back();
      const int n = a.count + b.count;
      a = {(a.log_attribute * a.count + b.log_attribute * b.count) / n, (a.log_rate * a.count + b.log_rate * b.count) / n, n};
    }
  }
  if (blocks.size() < 3)
    throw InputError("inverse map of the " + name_ + ": the trained " + name_ +
                     " does not fall as the rate grows (fewer than three points after pooling)");
  for (auto it = blocks.rbegin(); it != blocks.rend(); ++it) {
    attribute_.push_back(std::exp(it->log_attribute));
    rate_.push_back(std::exp(it->log_rate));
  }
}

std::optional<double> RateMap::rate_for(double attribute) const {
  if (!(attribute >= smallest() && attribute <= largest())) return std::nullopt;
  return interpolate(attribute_, rate_, attribute);
}

double RateMap::cross_validated_error() const {
  std::vector<double> log_errors;
  for (size_t leave = 1; leave + 1 < attribute_.size(); ++leave) {
    std::vector<double> a, r;
    for (size_t i = 0; i < attribute_.size(); ++i)
      if (i != leave) a.push_back(attribute_[i]), r.push_back(rate_[i]);
    log_errors.push_back(std::abs(std::log(interpolate(a, r, attribute_[leave]) / rate_[leave])));
  }
  return std::exp(median(log_errors)) - 1.0;
}

std::optional<double> scale_for_range(const RateMap& map, double smallest_wanted, double largest_wanted, double exponent) {
  const double lo = std::pow(smallest_wanted, 1.0 / exponent), hi = std::pow(largest_wanted, 1.0 / exponent);
  const double trained_lo = std::pow(map.smallest(), 1.0 / exponent), trained_hi = std::pow(map.largest(), 1.0 / exponent);
  if (lo >= trained_lo && hi <= trained_hi) return 1.0;
  if (hi / lo > trained_hi / trained_lo) return std::nullopt;
  return std::sqrt(lo * hi) / std::sqrt(trained_lo * trained_hi);
}

}  // namespace physarum
