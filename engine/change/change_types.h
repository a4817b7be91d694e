#pragma once
// Shared types of multi-session change detection: per-voxel labels (VoxelLabel,
// LabelBlock, LabelMap), the config (ChangeConfig) and the statistics of a session update
// (ChangeUpdateStats). They live beside the kernels that produce them (engine/kernels/change_*.h)
// so the engine's reference passes and device dispatch share them; this header is the host's
// name for them. The per-voxel rules are in kernels/change_rules.h.
#include "change/change_config.h"
#include "change/change_labels.h"
