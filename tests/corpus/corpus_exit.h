#pragma once

// What a corpus probe process tells its driver, and the bounds it runs under.
namespace sandphys::corpus {

inline constexpr int kExitBody = 0;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitNamedError = 3;
inline constexpr int kExitUnnamedError = 4;
inline constexpr int kExitOtherException = 5;

/// Largest extent a corpus mesh is scaled to, m, and the particle diameter it is sampled at, m.
inline constexpr double kFitMetres = 0.25;
inline constexpr float kDiameter = 0.02f;

/// Bounds of one probe: CPU seconds and address space.
inline constexpr unsigned kProbeCpuSeconds = 30;
inline constexpr unsigned long long kProbeBytes = 2ull << 30;

}  // namespace sandphys::corpus
