#include <algorithm>
#include <bit>
#include <vector>

#include "core/world_impl.h"
#include "gl/gl_check.h"
#include "gl/shader_library.h"
#include "sandphys/error.h"

namespace sandphys::detail {

// scan_blocks.comp reads whole blocks of the table without bounds checks.
constexpr std::uint32_t kMinTableSize = 4096;
static_assert(kMinTableSize % kScanBlock == 0);

std::uint32_t HashTable::sizeFor(std::uint32_t particles) {
  return std::max<std::uint32_t>(kMinTableSize,
                                 std::bit_ceil(std::max<std::uint32_t>(particles, 1u)));
}

HashTable HashTable::forParticles(std::uint32_t particles) {
  HashTable t;
  t.size = sizeFor(particles);
  const std::uint32_t mask = t.size - 1u;
  // Like a dense grid of side ~size^(1/3): nearby cells get nearby buckets.
  std::uint32_t side = 1;
  while (side * side * side < t.size) side *= 2;
  auto distinct = [&](std::uint32_t my, std::uint32_t mz) {
    for (int dz = -2; dz <= 2; ++dz)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          if (!dx && !dy && !dz) continue;
          std::uint32_t h = std::uint32_t(dx) + std::uint32_t(dy) * my + std::uint32_t(dz) * mz;
          if ((h & mask) == 0u) return false;
        }
    return true;
  };
  for (std::uint32_t my = side + 1;; my += 2) {
    std::uint32_t mz = my * side + 3;
    if (distinct(my, mz)) {
      t.multiplierY = my;
      t.multiplierZ = mz;
      return t;
    }
  }
}

void WorldBuffers::allocate(std::uint32_t bodies, std::uint32_t particles, std::uint32_t tableSize,
                            std::uint32_t colliders, std::uint32_t bodiesInUse,
                            std::uint32_t particlesInUse, bool history, bool rollingHistory,
                            bool sleeping, bool sorting) {
  const std::uint32_t grids = sleeping ? 2u : 1u;
  for (unsigned b = 0; b < kBindingCount; ++b) {
    const GpuBufferSpec& spec = kGpuBuffers[b];
    std::size_t count = 1;
    std::size_t keep = 0;
    switch (spec.sizedBy) {
      case SizedBy::Bodies:
        count = bodies;
        keep = bodiesInUse;
        break;
      case SizedBy::Particles:
        count = particles;
        keep = particlesInUse;
        break;
      case SizedBy::SleepBodies:
        count = sleeping ? bodies : 1;
        keep = sleeping ? bodiesInUse : 0;
        break;
      case SizedBy::SleepParticles:
        count = sleeping ? particles : 1;
        keep = sleeping ? particlesInUse : 0;
        break;
      case SizedBy::SleepChunks:
        // A cache, taken back to "scan" whenever bodies change (World::Impl::prepareBodies).
        count = sleeping ? (std::size_t(bodies) + kCollectChunk - 1) / kCollectChunk : 1;
        break;
      case SizedBy::OrderBodies:
        count = sorting ? bodies : 1;  // written anew by each sort
        break;
      case SizedBy::Lists:
        count = particles;
        break;
      case SizedBy::AwakeLists:
        count = sleeping ? 1 : particles;
        break;
      case SizedBy::History:
        count = history ? particles : 1;
        keep = history ? particlesInUse : 0;
        break;
      case SizedBy::RollingHistory:
        count = rollingHistory ? particles : 1;
        keep = rollingHistory ? particlesInUse : 0;
        break;
      case SizedBy::Table:
        count = std::size_t(tableSize) * grids;
        break;
      case SizedBy::TablePlusOne:
        count = (std::size_t(tableSize) + 1u) * grids;
        break;
      case SizedBy::ScanBlocks:
        count = std::size_t((tableSize + kScanBlock - 1) / kScanBlock) * grids;
        break;
      case SizedBy::GridParticles:
        count = std::size_t(particles) * grids;
        break;
      case SizedBy::Colliders:
        count = colliders;
        keep = colliders;
        break;
      case SizedBy::Fixed:
        count = 1;
        keep = 1;
        break;
    }
    const std::size_t bytes = count * spec.unitBytes();
    gl::Buffer& buffer = storage[b];
    if (buffer.id() == 0) {
      buffer = gl::Buffer(bytes, spec.array);
    } else if (bytes > buffer.size()) {
      if (spec.sizedBy == SizedBy::Table || spec.sizedBy == SizedBy::TablePlusOne ||
          spec.sizedBy == SizedBy::ScanBlocks || spec.sizedBy == SizedBy::GridParticles ||
          spec.sizedBy == SizedBy::Lists || spec.sizedBy == SizedBy::AwakeLists) {
        buffer = gl::Buffer(bytes, spec.array);  // rebuilt from the particles: nothing to keep
      } else {
        buffer.grow(bytes, keep * spec.unitBytes());
      }
    }
  }
  if (params.id() == 0) params = gl::Buffer(sizeof(SimParams), "SimParams");
  // The texture views follow the buffers (a grown buffer is a new buffer object).
  if (textures[0] == 0)
    glCreateTextures(GL_TEXTURE_BUFFER, GLsizei(textures.size()), textures.data());
  for (unsigned b = 0; b < kBindingCount; ++b) {
    const GpuBufferSpec& spec = kGpuBuffers[b];
    if (spec.textureUnit != kNoTextureUnit)
      glTextureBuffer(textures[spec.textureUnit], viewFormat(spec.element), storage[b].id());
  }
  gl::check("allocating world buffers");
}

WorldBuffers::~WorldBuffers() {
  if (textures[0]) glDeleteTextures(GLsizei(textures.size()), textures.data());
}

void WorldBuffers::bindAll() const {
  for (unsigned b = 0; b < kBindingCount; ++b) storage[b].bindBase(GL_SHADER_STORAGE_BUFFER, b);
  // The list build's passes take their group counts from the counters (list_check.comp).
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, storage[kCounters].id());
  params.bindBase(GL_UNIFORM_BUFFER, kSimParamsBinding);
  for (GLuint unit = 0; unit < textures.size(); ++unit) glBindTextureUnit(unit, textures[unit]);
  for (const GpuBufferSpec& spec : kGpuBuffers) {
    if (spec.imageUnit == kNoImageUnit) continue;
    glBindImageTexture(spec.imageUnit, textures[spec.textureUnit], 0, GL_FALSE, 0, GL_READ_WRITE,
                       viewFormat(spec.element));
  }
}

std::vector<BufferMemory> WorldBuffers::byBuffer() const {
  std::vector<BufferMemory> out;
  out.reserve(kBindingCount + 1);
  for (std::size_t b = 0; b < kBindingCount; ++b) {
    out.push_back({kGpuBuffers[b].array, storage[b].size()});
  }
  out.push_back({"params", params.size()});
  return out;
}

std::uint64_t WorldBuffers::bytes() const {
  std::uint64_t total = 0;
  for (const BufferMemory& buffer : byBuffer()) total += buffer.bytes;
  return total;
}

void WorldKernels::compile(ContactLaw law, bool sleeping, bool rollingFriction, bool sorting,
                           bool searchEvery) {
  gl::ShaderLibrary library;
  std::vector<std::string> defines;
  if (law == ContactLaw::PaperViscous) defines.push_back("PAPER_LAW 1");
  if (sleeping) defines.push_back("SLEEPING 1");
  if (rollingFriction) defines.push_back("ROLLING_FRICTION 1");
  auto compile = [&](const char* name, std::vector<std::string> extra = {}) {
    extra.insert(extra.end(), defines.begin(), defines.end());
    return library.compileCompute(name, extra);
  };
  bodiesToParticles = compile("sim/bodies_to_particles.comp");
  listCheck = compile("sim/list_check.comp");
  gridExtent = compile("sim/grid_extent.comp");
  gridCount = compile("sim/grid_count.comp");
  scanBlocks = compile("sim/scan_blocks.comp");
  scanBlockSums = compile("sim/scan_block_sums.comp");
  scanAdd = compile("sim/scan_add.comp");
  gridScatter = compile("sim/grid_scatter.comp");
  gridSort = compile("sim/grid_sort.comp");
  // Without sleep the build and the near marking list the particles the contacts pass leaves to
  // the search and to the collider pass.
  const std::vector<std::string> every =
      searchEvery ? std::vector<std::string>{"SEARCH_EVERY 1"} : std::vector<std::string>{};
  listBuild = compile("sim/list_build.comp", every);
  if (!sleeping) listNear = compile("sim/list_near.comp", every);
  contacts = compile("sim/contacts.comp", every);
  contactList = compile("sim/contacts.comp", {"CONTACT_LIST 1"});
  contactsSearch = compile("sim/contacts.comp", {"SEARCHING 1"});
  if (!sleeping) contactsColliders = compile("sim/contacts.comp", {"COLLIDERS_PASS 1"});
  integrateBodies = compile("sim/integrate_bodies.comp");
  integrateLargeBodies = compile("sim/integrate_large_bodies.comp");
  if (law == ContactLaw::HertzMindlin) countPairs = compile("sim/count_pairs.comp");
  statsReduce = compile("sim/stats_reduce.comp");
  resetPeakOverlap = compile("sim/reset_peak_overlap.comp");
  stateHash = compile("sim/state_hash.comp");
  spawnCheck = compile("sim/spawn_check.comp");
  if (sleeping) {
    wakeRegion = compile("sim/wake_region.comp");
    collectActive = compile("sim/collect_active.comp");
  }
  if (sorting) {
    orderSequence = compile("sim/order_sequence.comp");
    orderSources = compile("sim/order_sources.comp");
    orderSlots = compile("sim/order_slots.comp");
    orderMoves = compile("sim/order_moves.comp");
    orderPack = compile("sim/order_pack.comp");
    orderGather = compile("sim/order_gather.comp");
    if (law == ContactLaw::HertzMindlin) orderKeys = compile("sim/order_keys.comp");
  }
}

void WorldKernels::release() {
  for (GLuint p : {bodiesToParticles,
                   listCheck,
                   gridExtent,
                   gridCount,
                   scanBlocks,
                   scanBlockSums,
                   scanAdd,
                   gridScatter,
                   gridSort,
                   listBuild,
                   listNear,
                   contacts,
                   contactList,
                   contactsSearch,
                   contactsColliders,
                   integrateBodies,
                   integrateLargeBodies,
                   countPairs,
                   statsReduce,
                   resetPeakOverlap,
                   stateHash,
                   spawnCheck,
                   wakeRegion,
                   collectActive,
                   orderSequence,
                   orderSources,
                   orderSlots,
                   orderMoves,
                   orderPack,
                   orderGather,
                   orderKeys}) {
    if (p) glDeleteProgram(p);
  }
  *this = {};
}

}  // namespace sandphys::detail
