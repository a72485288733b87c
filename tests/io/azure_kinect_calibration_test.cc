// ParseAzureCalibration against the factory calibration of the real recording
// (pyk4a_calibration.json, the same text as the recording's attachment), and bad fields.

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "simtree/core/error.h"
#include "simtree/io/azure_kinect.h"
#include "test_util.h"

namespace simtree {
namespace {

std::string CalibrationText() {
  return test::ReadText(test::SharedData("azure-kinect/pyk4a_calibration.json"));
}

AzureCalibration Parse(const std::string& text, int depth_w = 640, int depth_h = 576,
                       int color_w = 1280, int color_h = 720) {
  return ParseAzureCalibration(text, "calib.json", depth_w, depth_h, color_w, color_h);
}

TEST(AzureCalibration, ScalesTheFactoryNumbersToTheRecordedModes) {
  const AzureCalibration c = Parse(CalibrationText());
  // Depth, NFOV unbinned: the 640x576 window at (192, 180) of the 1024x1024 sensor; pixel
  // centres at integers (-0.5).
  EXPECT_NEAR(c.depth.cx, 0.5129697918891907 * 1024 - 192 - 0.5, 1e-9);
  EXPECT_NEAR(c.depth.cy, 0.5169235467910767 * 1024 - 180 - 0.5, 1e-9);
  EXPECT_NEAR(c.depth.fx, 0.4927808940410614 * 1024, 1e-9);
  EXPECT_NEAR(c.depth.fy, 0.49290284514427185 * 1024, 1e-9);
  EXPECT_DOUBLE_EQ(c.depth.k1, 0.5479397773742676);
  EXPECT_DOUBLE_EQ(c.depth.k6, -0.013910384848713875);
  EXPECT_DOUBLE_EQ(c.depth.p2, -7.210415787994862e-05);  // stored before p1
  EXPECT_DOUBLE_EQ(c.depth.p1, 2.0557534298859537e-05);
  EXPECT_DOUBLE_EQ(c.depth.metric_radius, 1.739999771118164);
  EXPECT_EQ(c.depth.width, 640);
  EXPECT_EQ(c.depth.height, 576);
  // Colour 720p: the 4096x2304 band at y = 384 of the 4096x3072 sensor, scaled by 1280/4096.
  const double s = 1280.0 / 4096;
  EXPECT_NEAR(c.color.cx, 0.4998471438884735 * 4096 * s - 0.5, 1e-9);
  EXPECT_NEAR(c.color.cy, (0.5066176056861877 * 3072 - 384) * s - 0.5, 1e-9);
  EXPECT_NEAR(c.color.fx, 0.4779651165008545 * 4096 * s, 1e-9);
  EXPECT_NEAR(c.color.fy, 0.6374239325523376 * 3072 * s, 1e-9);
  EXPECT_DOUBLE_EQ(c.color.k2, -2.489396572113037);
  EXPECT_DOUBLE_EQ(c.color.metric_radius, 0.0);
  // Depth to colour: the colour camera's pose (the depth camera's is the identity).
  EXPECT_NEAR(c.depth_to_color.translation_m.x(), -0.032083429396152496, 1e-12);
  EXPECT_NEAR(c.depth_to_color.translation_m.z(), 0.003883692668750882, 1e-12);
  EXPECT_NEAR(c.depth_to_color.rotation(1, 2), 0.0861603245139122, 1e-12);
  EXPECT_EQ(c.serial, "001514394512");
}

TEST(AzureCalibration, OtherModesScaleFromTheSameSensor) {
  const AzureCalibration wfov = Parse(CalibrationText(), 512, 512, 2048, 1536);
  EXPECT_NEAR(wfov.depth.cx, 0.5129697918891907 * 512 - 0.5, 1e-9);
  EXPECT_NEAR(wfov.color.cy, 0.5066176056861877 * 1536 - 0.5, 1e-9);
  const AzureCalibration binned = Parse(CalibrationText(), 320, 288, 1920, 1080);
  EXPECT_NEAR(binned.depth.cy, (0.5169235467910767 * 1024 - 180) * 0.5 - 0.5, 1e-9);
  EXPECT_NEAR(binned.color.fx, 0.4779651165008545 * 1920, 1e-9);
}

TEST(AzureCalibration, TheRecordingCarriesTheSameCalibration) {
  AzureKinectReader reader(test::SharedData("azure-kinect/pyk4a_recording.mkv"));
  EXPECT_EQ(nlohmann::json::parse(reader.calibration_json()),
            nlohmann::json::parse(CalibrationText()));
  const AzureCalibration c = reader.calibration();
  EXPECT_DOUBLE_EQ(c.depth.fx, Parse(CalibrationText()).depth.fx);
}

// The calibration with `edit` applied to its JSON; the InputError's message.
template <typename Edit>
std::string ErrorAfter(Edit edit, int depth_w = 640, int depth_h = 576) {
  nlohmann::json doc = nlohmann::json::parse(CalibrationText());
  edit(doc["CalibrationInformation"]["Cameras"]);
  return test::ErrorOf<InputError>([&] { Parse(doc.dump(), depth_w, depth_h); });
}

TEST(AzureCalibration, BadFieldsAreErrorsNamingTheField) {
  EXPECT_NE(ErrorAfter([](nlohmann::json& cams) {
              cams[0]["Intrinsics"].erase("ModelParameters");
            }).find("Cameras[0].Intrinsics.ModelParameters: missing"),
            std::string::npos);
  const std::string short_list =
      ErrorAfter([](nlohmann::json& cams) { cams[1]["Intrinsics"]["ModelParameters"].erase(3); });
  EXPECT_NE(short_list.find("Cameras[1].Intrinsics.ModelParameters: expected 14 numbers, got 13"),
            std::string::npos)
      << short_list;
  const std::string model = ErrorAfter(
      [](nlohmann::json& cams) { cams[0]["Intrinsics"]["ModelType"] = "CALIBRATION_Rational6KT"; });
  EXPECT_NE(model.find("ModelType: expected CALIBRATION_LensDistortionModelBrownConrady"),
            std::string::npos)
      << model;
  const std::string no_color = ErrorAfter([](nlohmann::json& cams) { cams.erase(1); });
  EXPECT_NE(no_color.find("CALIBRATION_CameraPurposePhotoVideo"), std::string::npos) << no_color;
  const std::string rotation =
      ErrorAfter([](nlohmann::json& cams) { cams[1]["Rt"]["Rotation"][0] = 2.0; });
  EXPECT_NE(rotation.find("Cameras[1].Rt.Rotation: expected a rotation"), std::string::npos)
      << rotation;
  const std::string size = ErrorAfter([](nlohmann::json&) {}, 640, 480);
  EXPECT_NE(size.find("DEPTH track: expected a depth mode's size"), std::string::npos) << size;
  EXPECT_NE(
      test::ErrorOf<InputError>([] { Parse("{\"CalibrationInformation\": 3"); }).find("calib.json"),
      std::string::npos);
}

}  // namespace
}  // namespace simtree
