#pragma once
// Shards, for schedulers without MPI (job arrays): `closurelab run SPEC --out DIR --shard i/N` computes the i-th of
// N shares of the matrix into DIR/cells/ (each shard under its own lock, so the N shards may run at once on one
// folder) and leaves a note DIR/shards/<i>-of-<N>.json (spec, spec file, its cells); it writes no table.
// `closurelab merge DIR` checks that every cell of the matrix is there and writes the table a single run would
// have written.
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"

namespace closurelab {

struct Shard {
  int index = 0;
  int count = 0;  // 0: not sharded
  bool active() const { return count > 0; }
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};

// Parses "i/N" (0 <= i < N, N >= 1, plain decimal integers); throws ConfigError at "--shard" otherwise.
Shard parse_shard(const std::string& text);

// The shard of each cell: cost-balanced (largest expected cost first, each to the shard with the least expected
// cost so far; ties to the lower shard), a function of the costs alone, so every shard computes the same split.
std::vector<int> assign_shards(const std::vector<double>& costs, int count);

// The lock file of a shard in DIR (".closurelab.shard-<i>-of-<N>.lock").
std::string shard_lock_name(const Shard& shard);

// Writes DIR/shards/<i>-of-<N>.json: {"shard", "count", "spec", "spec_file", "cells" (ids), "complete"}.
void write_shard_note(const std::string& dir, const Shard& shard, const json& spec, const std::string& spec_file,
                      const std::vector<std::string>& cell_ids, bool complete);

// `closurelab merge DIR`: returns the exit code (0 table written, 1 a cell had failed or a write failed,
// 2 no shard notes, notes that disagree, an invalid spec, missing, truncated, edited or unsealed cells (each
// listed, with the shards to run; results_table.hpp read_cell) or the folder in use).
int merge_shards(const std::string& dir, const Registry& registry, const std::string& command_line);

}  // namespace closurelab
