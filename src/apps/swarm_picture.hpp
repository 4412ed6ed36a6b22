#pragma once
// swarm.png: what the first robot's merged map looks like with everyone on it.
#include <optional>
#include <vector>

#include "grid/grid_raster.hpp"
#include "io/maps/render.hpp"
#include "eval/swarm_run.hpp"

namespace dsswarm {

// `raster` (the first agent's merged map) with every path the first agent can
// place (`frames[i]`: agent i's map frame in agent 0's), each in its colour
// from a disc where it started, the encounters (black disc: accepted, red
// ring: rejected), and below it a legend and a scale bar. Another robot's path
// past the last map of it the first agent holds (SwarmAgentResult::map_versions)
// is drawn pale: the ground it crossed then is not in that map.
Image swarm_picture(const SwarmRunResult& run, const GridRaster& raster,
                    const std::vector<std::optional<Pose2>>& frames);

// The colour of a path past the map held: `c` most of the way to white.
Rgb pale(Rgb c);

}  // namespace dsswarm
