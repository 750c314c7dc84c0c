// What a command is doing, for the one message luxel prints when memory runs out: std::bad_alloc
// says nothing of what was being allocated, or what to change. Commands set the activity as they
// go (loading, solving, rendering); main() catches std::bad_alloc once and prints
// outOfMemoryMessage().
#pragma once

#include <string>

namespace luxel::cli {

// `doing`: "solving scene 'cornell' (--elements 2000000)"; `hint`: what to reduce, naming options.
void nowDoing(std::string doing, std::string hint);
// "out of memory while DOING: HINT", or a general message before any activity was set.
std::string outOfMemoryMessage();

}  // namespace luxel::cli
