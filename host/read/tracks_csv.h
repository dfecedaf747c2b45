// Reader of the tracks.csv that `evms run` writes (host/write/event_writers.h), for scoring:
//   t_us,track_id,state,x,y,vx,vy[,further columns]
// state is tentative or confirmed. Columns after vy (evms writes the cluster's event count, its
// bounding box and the position covariance) are checked for their count and otherwise left
// alone, so that a file with more columns still scores. Comment lines before the header are
// skipped. A bad row stops with the file, its line and what is wrong.
#pragma once

#include <string>
#include <vector>

#include "types/event.h"

namespace evms::read {

std::vector<TrackUpdate> read_tracks_csv(const std::string& path);

}  // namespace evms::read
