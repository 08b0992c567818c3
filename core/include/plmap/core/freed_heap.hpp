#pragma once
/// \file
/// Giving memory that the program freed back to the system.

namespace plmap {

/// Gives the memory freed into malloc's heap back to the system (glibc's malloc_trim; elsewhere
/// nothing). Freed blocks in the middle of the heap stay resident until they are used again, so
/// after a step that frees much, the steps that allocate anew would stand on top of them. Costs a
/// walk over the heap's free blocks (about 1.5 ms with a 25 MiB heap), so it is called where a
/// peak is at stake: in MapBuilder::finalize, and after a face removal (face_removal.hpp).
void give_freed_heap_back();

}  // namespace plmap
