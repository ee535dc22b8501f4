#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <sandphys/sandphys.h>

#include "measure.h"

namespace sandphys::bench {

/// A settled pile kept for later runs (--pile-cache): settling takes most of a run, an hour and
/// more at 64K granules, and the same options settle the same pile bit for bit.
struct SettledPile {
  std::uint32_t settleSteps = 0;     ///< substeps the pile settled
  std::uint32_t sleepWaitSteps = 0;  ///< and, with sleep, waited for the sand to fall asleep
  double settleWallSeconds = 0.0;    ///< the wall time the run that settled it took
  double peakOverlap = 0.0;          ///< the largest overlap while it settled, d (PileState)
};

/// What a settled pile depends on, as text: the scene's options (pileJson), the granules, the
/// substeps it settles and (with sleep) waits, and the hash of `world` as built, which changes
/// with the code that lays the pile out. `world` is the World the pile was just built in.
std::string settledPileKey(const MeasureOptions& options, const SizePlan& plan, World& world);

/// The file of the pile of `key` in `folder`: the scene, the granules and a hash of the key.
std::filesystem::path settledPileFile(const std::string& folder, const MeasureOptions& options,
                                      std::uint32_t granules, const std::string& key);

/// Restores `world` (the pile as built) to the settled pile in `file` when the file exists and
/// was written for `key`; nullopt otherwise. A file that cannot be read is named on stderr and
/// passed over, and the pile settles as without it.
std::optional<SettledPile> loadSettledPile(const std::filesystem::path& file,
                                           const std::string& key, World& world);

/// Writes the state of `world`, the pile of `key` just settled, to `file` (its folder created);
/// written beside it first and then renamed, so an interrupted run leaves no file behind. Throws
/// sandphys::Error naming the file when it cannot be written.
void saveSettledPile(const std::filesystem::path& file, const std::string& key,
                     const SettledPile& pile, World& world);

}  // namespace sandphys::bench
