#include "swarm/swarm_config.hpp"

#include <cmath>

#include "common/errors.hpp"

namespace dsswarm {

SlamConfig swarm_slam_config() {
  SlamConfig config;
  config.loop_closure.round_nodes = 20;
  return config;
}

void SwarmConfig::validate() const {
  slam.validate();
  encounter.validate();
  if (!(remerge_interval >= 0.0)) throw ConfigError("swarm.remerge_interval must be >= 0 s");
  if (!(merge_delay >= 0.0) || !std::isfinite(merge_delay))
    throw ConfigError("swarm.merge_delay must be a finite number of seconds >= 0");
  if (!(confirm_xy > 0.0) || !(confirm_theta > 0.0)) throw ConfigError("swarm.confirm_xy and confirm_theta must be > 0");
  if (!(exchange_timeout > 0.0)) throw ConfigError("swarm.exchange_timeout must be > 0 s");
  if (!(offer_timeout > 0.0)) throw ConfigError("swarm.offer_timeout must be > 0 s");
  if (chunk_bytes < 1024 || chunk_bytes > 512 * 1024) throw ConfigError("swarm.chunk_bytes must be in [1024, 524288]");
  if (max_open_encounters < 1) throw ConfigError("swarm.max_open_encounters must be >= 1");
  if (remembered_encounters < 1) throw ConfigError("swarm.remembered_encounters must be >= 1");
  if (max_transfer_bytes < (std::size_t{1} << 20)) throw ConfigError("swarm.max_transfer_bytes must be >= 1 MiB");
  if (!(repeat_xy >= 0.0) || !(repeat_theta >= 0.0)) throw ConfigError("swarm.repeat_xy and repeat_theta must be >= 0");
  if (repeat_retries < 0) throw ConfigError("swarm.repeat_retries must be >= 0");
  if (!(moves_interval >= 0.0)) throw ConfigError("swarm.moves_interval must be >= 0 s");
  if (max_followed_encounters < 1 || max_followed_encounters > 4096)
    throw ConfigError("swarm.max_followed_encounters must be in [1, 4096]");
  if (max_moved_closures > 8192) throw ConfigError("swarm.max_moved_closures must be in [0, 8192]");
  if (final_exchanges < 0 || final_exchanges > 100) throw ConfigError("swarm.final_exchanges must be in [0, 100]");
  if (max_pending_confirmations < 1 || max_pending_confirmations > 64)
    throw ConfigError("swarm.max_pending_confirmations must be in [1, 64]");
}

}  // namespace dsswarm
