// ptnet/paper.hpp: the constants PressureTransferNet fixes (paper Sec. 3),
// defined once; every stage reads them from here.
//
//   ptnet::MatSpec mat;                            // kMatRows x kMatCols cells of kMatPitchM
//   bool contact = kpa > ptnet::kContactKpa;       // the binary R^2's binarisation
//   const auto& d = ptnet::paper_distribution(Sex::male);  // 175 +- 15 cm, 75 +- 10 kg
//
// Dimension legend: T = kWindowFrames frames, H x W = kMatRows x kMatCols cells.
#pragma once

namespace ptnet {

inline constexpr int kWindowFrames = 30;     // T: frames per window (the network's channels)
inline constexpr int kWindowStride = 1;      // frames between window starts
inline constexpr double kFps = 30;           // frame rate (Hz); mocap is resampled to it
inline constexpr int kMatRows = 80;          // H: cells along the mat's long (walking) axis
inline constexpr int kMatCols = 28;          // W: cells across
inline constexpr double kMatPitchM = 0.02;   // cell size (m): a 1.60 m x 0.56 m mat
inline constexpr double kContactKpa = 0.5;   // a cell above this is in contact (binary R^2)
inline constexpr double kValFraction = 0.1;  // validation share of each motion's windows (the 9:1 split)

// Body attributes the tool accepts at its interfaces (CLI, CSV, datasets, models).
inline constexpr double kMinHeightCm = 100, kMaxHeightCm = 230;
inline constexpr double kMinWeightKg = 20, kMaxWeightKg = 250;

// The Gaussian body sets of the paper's protocol (training bodies, and the
// synthetic bodies of the HAR validation).
struct BodyDistribution {
  double height_mean_cm, height_sd_cm;
  double weight_mean_kg, weight_sd_kg;
};
inline constexpr BodyDistribution kPaperFemale{165, 15, 65, 10};
inline constexpr BodyDistribution kPaperMale{175, 15, 75, 10};

// The paper's Table 2: PressureTransferNet on its test bodies, RMSE and
// binary R^2 per motion category and on average, seen and unseen motions.
// Its RMSE is in its simulator's sensor units (PresSim's; the paper does not
// state them), not kPa: beside ours only in a table, never on a kPa axis.
struct PaperTable2Row {
  const char* category;  // walking | rom | freestyle | acting | average
  double seen_rmse, seen_binary_r2;      // RMSE in the paper's sensor units
  double unseen_rmse, unseen_binary_r2;
};
inline constexpr PaperTable2Row kPaperTable2[] = {
    {"walking", 8.72, 0.81, 12.46, 0.71},   {"rom", 9.21, 0.78, 12.89, 0.69},
    {"freestyle", 8.93, 0.80, 13.22, 0.70}, {"acting", 9.67, 0.76, 12.73, 0.69},
    {"average", 8.88, 0.79, 12.82, 0.70}};

}  // namespace ptnet
