#pragma once
// Shared types of multi-session change detection: per-voxel labels (VoxelLabel,
// LabelBlock, LabelMap), the config (ChangeConfig) and the statistics of a session update
// (ChangeUpdateStats), from change_config.h and change_labels.h, which the reference passes and
// the device dispatch share. The per-voxel rules are in change_rules.h.
#include "strata/change/change_config.h"
#include "strata/change/change_labels.h"
