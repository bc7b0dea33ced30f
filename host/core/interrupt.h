#pragma once
// Ctrl-C during a render only raises a flag, so the render loop can finish the pass in flight and
// write the image so far; a third Ctrl-C ends the process at once.
namespace kasha {

void install_interrupt_handler();
bool interrupt_requested();

}  // namespace kasha
