/* A launch's work items [item_first, item_end) (host/render/kernel_launcher.h). Every launch
 * starts at global offset 0, with its first item an argument: PoCL compiles a second work-group
 * function for a kernel launched at another offset, so passes split into launches would compile
 * each kernel twice. Launches are rounded up to whole work-groups: items from item_end return. */
#ifndef KASHA_SHARED_LAUNCH_RANGE_H
#define KASHA_SHARED_LAUNCH_RANGE_H

/* A kernel's last two parameters. */
#define KASHA_LAUNCH_RANGE int item_first, int item_end

/* The item this work item runs: get_global_id(0) is its index within the launch. */
inline int launch_item(int item_first) { return item_first + (int)get_global_id(0); }

#endif
