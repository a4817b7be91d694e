// Counting dynamic labels per dispatch without barriers: a subgroup sum, then one global atomic
// per subgroup that has any (dynamic labels are rare, so few atomics). Needs a `uint counters[]`
// buffer; call from uniform control flow (every invocation of the subgroup).
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require

void countDynamic(uint dynamic_labels, uint counter_index) {
  uint n = subgroupAdd(dynamic_labels);
  if (subgroupElect() && n > 0u) atomicAdd(counters[counter_index], n);
}
