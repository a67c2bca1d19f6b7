// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Which photos of tmr_reconstruct share a camera: folders of one size and
// one EXIF camera, or of numbered frames without EXIF, and photo headers
// read from JPEG files written with OpenImageIO.
#include "controllers/photo_extraction.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <vector>

namespace tmr {
namespace {

namespace fs = std::filesystem;

PhotoHeader Header(const std::string& name, int width, double focal = 0,
                   const std::string& make = "", const std::string& model = "") {
  PhotoHeader header;
  header.name = name;
  header.width = width;
  header.height = width * 3 / 4;
  header.make = make;
  header.model = model;
  header.focal_length = focal;
  return header;
}

TEST(FoldersOfOneCamera, OneSizeAndOneExifCameraOrVideoFrames) {
  std::vector<PhotoHeader> photos;
  for (int i = 1; i <= 20; ++i) {  // a video's frames: no EXIF, numbered
    char name[64];
    std::snprintf(name, sizeof(name), "video/frame%05d.png", i);
    photos.push_back(Header(name, 1280));
  }
  for (const char* name : {"phone/a.jpg", "phone/b.jpg", "phone/c.jpg"})
    photos.push_back(Header(name, 1024, 27.0));  // focal, no make or model
  for (const char* name : {"dslr/x.jpg", "dslr/y.jpg"})
    photos.push_back(Header(name, 3000, 35.0, "Canon", "EOS"));
  // Not one camera: two sizes; two focal lengths; unnumbered without EXIF;
  // a photo alone in the top folder.
  photos.push_back(Header("sizes/1.jpg", 1024, 27.0));
  photos.push_back(Header("sizes/2.jpg", 2048, 27.0));
  photos.push_back(Header("zoom/1.jpg", 1024, 27.0));
  photos.push_back(Header("zoom/2.jpg", 1024, 50.0));
  photos.push_back(Header("web/cat.jpg", 800));
  photos.push_back(Header("web/dog.jpg", 800));
  photos.push_back(Header("alone.jpg", 800, 30.0));
  EXPECT_EQ(FoldersOfOneCamera(photos),
            (std::vector<std::string>{"dslr", "phone", "video"}));
  EXPECT_EQ(FolderOf("video/frame00001.png"), "video");
  EXPECT_EQ(FolderOf("a/b/c.jpg"), "a/b");
  EXPECT_EQ(FolderOf("alone.jpg"), "");
}

TEST(ReadPhotoHeader, SizeAndExifWithoutThePixels) {
  const fs::path dir = fs::temp_directory_path() /
                       ("photo_extraction_test_" + std::to_string(::getpid()));
  fs::create_directories(dir / "sub");
  const std::string path = (dir / "sub" / "photo.jpg").string();
  OIIO::ImageSpec spec(64, 48, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("Make", "Acme");
  spec.attribute("Model", "Cam 1");
  spec.attribute("Exif:FocalLength", 4.5f);
  std::vector<unsigned char> pixels(64 * 48 * 3, 128);
  {
    auto output = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(output && output->open(path, spec));
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    output->close();
  }
  PhotoHeader header;
  ASSERT_TRUE(ReadPhotoHeader(path, &header));
  EXPECT_EQ(header.width, 64);
  EXPECT_EQ(header.height, 48);
  EXPECT_EQ(header.make, "Acme");
  EXPECT_EQ(header.model, "Cam 1");
  EXPECT_FLOAT_EQ(header.focal_length, 4.5);
  EXPECT_FALSE(ReadPhotoHeader((dir / "missing.jpg").string(), &header));

  std::vector<std::string> names;
  std::string error;
  ASSERT_TRUE(ListPhotos(dir.string(), &names, &error)) << error;
  EXPECT_EQ(names, std::vector<std::string>{"sub/photo.jpg"});
  fs::remove_all(dir);
  EXPECT_FALSE(ListPhotos(dir.string(), &names, &error));
  EXPECT_EQ(error.rfind("cannot read '" + dir.string() + "': ", 0), 0u);
}

}  // namespace
}  // namespace tmr
