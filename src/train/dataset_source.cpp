// ptnet::Dataset (the HDF5 file of the data stage) as a PressureSource.
#include "ptnet/data.hpp"
#include "ptnet/train.hpp"

namespace ptnet {
namespace {

class DatasetSource : public PressureSource {
 public:
  explicit DatasetSource(Dataset d) : d_(std::move(d)) {}
  std::string path() const override { return d_.path(); }
  MatSpec mat() const override { return d_.info().mat; }
  double fps() const override { return d_.info().fps; }
  const std::vector<BodySpec>& bodies() const override { return d_.bodies(); }
  const std::vector<SequenceMeta>& sequences() const override { return d_.sequences(); }
  void read(const std::string& name, int start, int count, float* out) const override {
    d_.read(name, start, count, out);
  }

 private:
  Dataset d_;
};

}  // namespace

std::unique_ptr<PressureSource> open_dataset_source(const std::string& path) {
  return std::make_unique<DatasetSource>(Dataset::open(path));
}

}  // namespace ptnet
