/* vpl_selection: the names of the vpl method's selection rules (vpl_select.h says what each
 * does), apart so that settings (renderer_desc.h) can name a rule without the VPL types. */
#ifndef CAVELIGHT_VPL_SELECTION_H
#define CAVELIGHT_VPL_SELECTION_H

typedef enum vpl_selection {
    VPL_SELECT_FLUX = 0,
    VPL_SELECT_VIEW,
    VPL_SELECT_REGULAR,
    VPL_SELECT_COUNT
} vpl_selection;
/* "flux", "view", "regular": the rules' names, for options and reports. */
extern const char *const vpl_selection_names[VPL_SELECT_COUNT];

#endif
