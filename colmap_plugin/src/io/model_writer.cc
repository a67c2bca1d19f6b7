// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "io/model_writer.h"

#include <colmap/scene/reconstruction_io_binary.h>
#include <colmap/util/endian.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <streambuf>
#include <utility>
#include <vector>

namespace tmr {
namespace {

namespace fs = std::filesystem;

constexpr const char* kFileNames[] = {"rigs.bin", "cameras.bin", "frames.bin",
                                      "images.bin", "points3D.bin"};

// Passes every byte written to it on to `out` but the first eight: the
// record count that COLMAP's binary writers put first, kept for Count().
class CountlessBuffer : public std::streambuf {
 public:
  explicit CountlessBuffer(std::streambuf* out) : out_(out) {}

  uint64_t Count() const {
    uint64_t count = 0;
    std::memcpy(&count, header_, sizeof(count));
    return colmap::LittleEndianToNative(count);
  }

 protected:
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    std::streamsize used = 0;
    while (header_size_ < sizeof(header_) && used < n)
      header_[header_size_++] = s[used++];
    if (used == n) return n;
    return used + out_->sputn(s + used, n - used);
  }

  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof()))
      return traits_type::not_eof(c);
    const char ch = traits_type::to_char_type(c);
    return xsputn(&ch, 1) == 1 ? c : traits_type::eof();
  }

 private:
  std::streambuf* out_;
  char header_[sizeof(uint64_t)] = {};
  size_t header_size_ = 0;
};

}  // namespace

ModelWriter::ModelWriter(std::string path)
    : path_(std::move(path)), temporary_(path_ + ".tmp") {}

ModelWriter::~ModelWriter() {
  if (finished_) return;
  for (std::ofstream& file : files_) file.close();
  std::error_code ec;
  fs::remove_all(temporary_, ec);
}

bool ModelWriter::Open() {
  std::error_code ec;
  fs::remove_all(temporary_, ec);
  fs::create_directories(temporary_, ec);
  if (ec) return false;
  for (int f = 0; f < kNumFiles; ++f) {
    files_[f].open(fs::path(temporary_) / kFileNames[f],
                   std::ios::trunc | std::ios::binary);
    colmap::WriteBinaryLittleEndian<uint64_t>(&files_[f], 0);  // the count
    if (!files_[f].good()) return false;
  }
  return true;
}

template <typename Write>
bool ModelWriter::AppendRecords(File f, const Write& write) {
  CountlessBuffer buffer(files_[f].rdbuf());
  std::ostream out(&buffer);
  try {
    write(out);
  } catch (const std::exception&) {
    return false;
  }
  if (!out.good()) return false;
  counts_[f] += buffer.Count();
  return true;
}

bool ModelWriter::Append(colmap::Reconstruction* part) {
  // New ids above both the ids written before and the part's own, so that
  // no new id meets an old one still in the part.
  std::vector<colmap::point3D_t> ids;
  ids.reserve(part->NumPoints3D());
  for (const auto& [id, point] : part->Points3D()) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  colmap::point3D_t next =
      std::max(last_point_id_, ids.empty() ? 0 : ids.back()) + 1;
  for (const colmap::point3D_t id : ids) {
    colmap::Point3D point = part->Point3D(id);
    part->DeletePoint3D(id);
    part->AddPoint3D(next++, std::move(point));
  }
  last_point_id_ = next - 1;
  // The cameras and rigs of its registered images that no earlier part
  // wrote (a model read from disk holds the cameras of all its images); a
  // rig's cameras must be in the model it is added to.
  colmap::Reconstruction new_cameras, new_rigs;
  for (const colmap::image_t id : part->RegImageIds()) {
    const colmap::Image& image = part->Image(id);
    const colmap::Camera& camera = part->Camera(image.CameraId());
    if (written_cameras_.insert(camera.camera_id).second) {
      new_cameras.AddCamera(camera);
    }
    const colmap::Rig& rig = part->Rig(part->Frame(image.FrameId()).RigId());
    if (written_rigs_.insert(rig.RigId()).second) {
      std::vector<colmap::sensor_t> sensors = {rig.RefSensorId()};
      for (const auto& [sensor, sensor_from_rig] : rig.NonRefSensors())
        sensors.push_back(sensor);
      for (const colmap::sensor_t& sensor : sensors) {
        if (sensor.type == colmap::SensorType::CAMERA &&
            !new_rigs.ExistsCamera(sensor.id))
          new_rigs.AddCamera(part->Camera(sensor.id));
      }
      new_rigs.AddRig(rig);
    }
  }
  return AppendRecords(kRigs,
                       [&](std::ostream& out) {
                         colmap::WriteRigsBinary(new_rigs, out);
                       }) &&
         AppendRecords(kCameras,
                       [&](std::ostream& out) {
                         colmap::WriteCamerasBinary(new_cameras, out);
                       }) &&
         AppendRecords(kFrames,
                       [&](std::ostream& out) {
                         colmap::WriteFramesBinary(*part, out);
                       }) &&
         AppendRecords(kImages,
                       [&](std::ostream& out) {
                         colmap::WriteImagesBinary(*part, out);
                       }) &&
         AppendRecords(kPoints3D, [&](std::ostream& out) {
           colmap::WritePoints3DBinary(*part, out);
         });
}

bool ModelWriter::Finish() {
  for (int f = 0; f < kNumFiles; ++f) {
    files_[f].seekp(0);
    colmap::WriteBinaryLittleEndian<uint64_t>(&files_[f], counts_[f]);
    files_[f].close();
    if (files_[f].fail()) return false;
  }
  std::error_code ec;
  fs::remove_all(path_, ec);
  fs::rename(temporary_, path_, ec);
  if (ec) return false;
  finished_ = true;
  return true;
}

}  // namespace tmr
