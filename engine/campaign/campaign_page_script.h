// The campaign page's own script (campaign_page.h): it reads the page's data (the JSON in
// <script id="hitl-campaign-data">) and draws with dygraphs each number criterion's spread across
// the seeds of each cell of the matrix (min to max as a whisker, the median as a dot, the limit
// dashed) and each criterion's trend over the history's runs (the mean, the worst, how many flights
// broke it; the latest run shaded red when it is a regression); the values under the cursor above
// each plot. It leaves window.hitlCampaign = {graphs, ids, drawn_ms} for tests and the console.
#pragma once

namespace hitl::campaign {

extern const char* const kCampaignPageScript;

}  // namespace hitl::campaign
