// A curtain dragged 20 cm deep through a framed one comes back through it when let go, in the drape
// (tests/common/untangle_support.h). At that depth the tip lies well behind the back curtain, whose penalty, where the
// cloth has crossed, would push it further back: the whole side cut off by the crossing takes no part in self-contact
// (newton/contact/self_contact.h), not only the crossing triangles.
#include "untangle_support.h"

namespace drape {
namespace {

TEST(Untangle, ACurtainDraggedFarThroughAnotherComesBackWhenLetGoInTheDrape) {
  test::draggedThroughComesBack("drape", 0.2);
}

}  // namespace
}  // namespace drape
