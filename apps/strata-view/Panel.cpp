// The Dear ImGui panel: file and load state, view and render settings,
// frame figures, the camera as a strata-render argument, and the CSG tree.
#include "Viewer.h"

#define GLFW_INCLUDE_NONE
#include <cstdio>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <string>

#include "strata/scene/SceneLoad.h"
#include "strata/core/InputFile.h"
#include "strata/io/ExportFormats.h"
#include "strata/render/ColorScheme.h"

namespace strata::view {
namespace {

const ImVec4 kErrorColor{1.0f, 0.45f, 0.4f, 1.0f};

constexpr std::array<const char*, kDebugViews> kDebugNames{"shaded", "depth", "normal", "peel layers", "forms"};

// Before the next item of a row: on the same line where `label` fits beside
// the last item, else on a line of its own. `box`: a check box or radio
// button (its square before the text), else a button.
void nextInRow(float width) {
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    if (ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width <= right) ImGui::SameLine();
}

void nextInRow(const char* label, bool box) {
    const ImGuiStyle& style = ImGui::GetStyle();
    const float text = ImGui::CalcTextSize(label, nullptr, true).x;
    nextInRow(box ? ImGui::GetFrameHeight() + style.ItemInnerSpacing.x + text : text + 2 * style.FramePadding.x);
}

// Text in the disabled colour, wrapped to the panel's width.
void disabledWrapped(const std::string& text) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", text.c_str());
    ImGui::PopStyleColor();
}

// Text wrapped to the panel's width at its spaces only (ImGui's own
// wrapping also breaks after a full stop, inside a number).
void wrappedAtSpaces(const std::string& text) {
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    const float space = ImGui::CalcTextSize(" ").x;
    bool first = true;
    std::size_t at = 0;
    while (at < text.size()) {
        std::size_t end = text.find(' ', at);
        if (end == std::string::npos) end = text.size();
        if (end > at) {
            const std::string word = text.substr(at, end - at);
            const float width = ImGui::CalcTextSize(word.c_str()).x;
            if (!first && ImGui::GetItemRectMax().x + space + width <= right) ImGui::SameLine(0.0f, space);
            if (width > ImGui::GetContentRegionAvail().x)
                ImGui::TextWrapped("%s", word.c_str());  // a word wider than the panel: broken where ImGui breaks it
            else
                ImGui::TextUnformatted(word.c_str());
            first = false;
        }
        at = end + 1;
    }
}

// A --camera= argument with a space after each comma, so that it wraps
// between numbers, never inside one.
std::string wrappableCamera(const std::string& line) {
    std::string out;
    for (char c : line) {
        out += c;
        if (c == ',') out += ' ';
    }
    return out;
}

// `text` as it fits in `width`: whole, or with its middle replaced by "..."
// (a file's name keeps its start and its extension), cut between UTF-8
// characters.
std::string ellipsized(const std::string& text, float width) {
    if (ImGui::CalcTextSize(text.c_str()).x <= width) return text;
    const auto shortened = [&](std::size_t keep) {
        std::size_t head = (keep + 1) / 2, tail = text.size() - keep / 2;
        while (head > 0 && (static_cast<unsigned char>(text[head]) & 0xC0) == 0x80) --head;
        while (tail < text.size() && (static_cast<unsigned char>(text[tail]) & 0xC0) == 0x80) ++tail;
        return text.substr(0, head) + "..." + text.substr(tail);
    };
    std::size_t fits = 0, over = text.size();  // the most characters kept that fit, found by halving
    while (over - fits > 1) {
        const std::size_t mid = (fits + over) / 2;
        (ImGui::CalcTextSize(shortened(mid).c_str()).x <= width ? fits : over) = mid;
    }
    return shortened(fits);
}

std::string formatted(const char* format, auto... values) {
    char text[256];
    std::snprintf(text, sizeof text, format, values...);
    return text;
}

}  // namespace

void Viewer::drawPanel() {
    // Docked at the left, as tall as the window; its right edge can be dragged.
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    const float height = viewport->Size.y;
    ImGui::SetNextWindowPos(viewport->Pos);
    if (requestedPanelWidth_) {
        ImGui::SetNextWindowSize(ImVec2(*requestedPanelWidth_, height), ImGuiCond_Always);
        requestedPanelWidth_.reset();
    } else {
        ImGui::SetNextWindowSize(ImVec2(panelWidth_, height), ImGuiCond_FirstUseEver);
    }
    ImGui::SetNextWindowSizeConstraints(ImVec2(220.0f, height), ImVec2(std::max(220.0f, widestPanel()), height));
    const bool open = ImGui::Begin("strata-view", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse);
    const float width = ImGui::GetWindowWidth();
    if (width != panelWidth_) {
        panelWidth_ = width;  // the view is sized to what is left on the next frame
        viewDirty_ = true;
    }
    overflowThisFrame_.clear();
    if (!open) {
        panelOverflow_.clear();
        ImGui::End();
        return;
    }
    ImGui::TextWrapped("%s", path_.c_str());
    // One status line, loading or not, so that the panel does not jump.
    if (loader_.busy()) {
        if (ImGui::SmallButton("cancel (Esc)")) loader_.cancel();
        ImGui::SameLine();
        const std::string step = loader_.progressText();
        ImGui::TextWrapped("loading... %.1f s%s%s", loader_.runningSeconds(), step.empty() ? "" : ": ", step.c_str());
    } else {
        disabledWrapped("shown; reloads when the file changes (F5: now)");
    }
    if (fileMissing_) {
        ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
        ImGui::TextWrapped("the file is gone (deleted or moved)");
        ImGui::PopStyleColor();
        disabledWrapped("(showing the last good version)");
    }
    if (!loadError_.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
        ImGui::TextWrapped("%s", loadError_.c_str());
        ImGui::PopStyleColor();
        disabledWrapped("(showing the last good version)");
    }
    if (!renderError_.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
        ImGui::TextWrapped("%s", renderError_.c_str());
        ImGui::PopStyleColor();
    }
    if (!scene_.tree.warnings.empty() &&
        ImGui::CollapsingHeader(("warnings (" + std::to_string(scene_.tree.warnings.size()) + ")").c_str(),
                                ImGuiTreeNodeFlags_DefaultOpen)) {
        for (const Warning& w : scene_.tree.warnings) ImGui::TextWrapped("%s", w.message.c_str());
    }
    noteOverflow("the file's state");

    drawOpenPanel();
    noteOverflow("open");

    if (ImGui::CollapsingHeader("view", ImGuiTreeNodeFlags_DefaultOpen)) {
        constexpr std::array<Preset, 7> presets{Preset::Top,  Preset::Bottom, Preset::Left,    Preset::Right,
                                                Preset::Front, Preset::Back,  Preset::Diagonal};
        for (std::size_t k = 0; k < presets.size(); ++k) {
            if (k != 0) nextInRow(presetName(presets[k]), false);
            if (ImGui::Button(presetName(presets[k]))) {
                orbit_.preset(presets[k]);
                viewDirty_ = true;
            }
        }
        nextInRow("view all", false);
        if (ImGui::Button("view all")) viewAllNow();
        bool ortho = projection_ == camera::Projection::Orthographic;
        if (ImGui::Checkbox("orthographic", &ortho)) toggleProjection();
        nextInRow("reset", false);
        if (ImGui::Button("reset")) resetView();
        bool axes = overlayOptions_.axes, scale = overlayOptions_.scale, edges = overlayOptions_.edges;
        if (ImGui::Checkbox("axes (Ctrl+2)", &axes)) setShowAxes(axes);
        nextInRow("scale markers", true);
        if (ImGui::Checkbox("scale markers", &scale)) setShowScale(scale);
        if (ImGui::Checkbox("edges (Ctrl+1)", &edges)) setShowEdges(edges);
    }
    noteOverflow("view");

    if (ImGui::CollapsingHeader("console", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::BeginChild("console lines", ImVec2(0, 120), true);
        for (const ConsoleLine& line : console_.lines()) {
            const bool colored = line.kind != ConsoleLine::Kind::Info;
            if (colored) {
                ImGui::PushStyleColor(ImGuiCol_Text, line.kind == ConsoleLine::Kind::Error     ? kErrorColor
                                                     : line.kind == ConsoleLine::Kind::Warning ? ImVec4(1.0f, 0.8f, 0.3f, 1.0f)
                                                                                               : ImVec4(0.6f, 0.9f, 1.0f, 1.0f));
            }
            ImGui::TextWrapped("%s", line.text.c_str());
            if (colored) ImGui::PopStyleColor();
        }
        // Follow the newest line unless the user scrolled up.
        if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY() - 1.0f) ImGui::SetScrollHereY(1.0f);
        noteOverflow("console");
        ImGui::EndChild();
    }
    noteOverflow("console");

    // A .scad is shown through OpenSCAD's CSG export, whose lines the
    // messages and the tree name where a node cannot be traced back to the
    // .scad: it can be saved to read them.
    if (!scene_.csgExport.empty() && ImGui::CollapsingHeader("CSG export", ImGuiTreeNodeFlags_DefaultOpen)) {
        const std::string fallback = defaultCsgExportPath(path_);
        char csg[1024];
        std::snprintf(csg, sizeof csg, "%s", csgExportPath_.c_str());
        ImGui::SetNextItemWidth(-1);
        if (ImGui::InputTextWithHint("##csgexport", fallback.c_str(), csg, sizeof csg)) csgExportPath_ = csg;
        if (ImGui::Button("save CSG export")) saveChosenCsgExport();
        disabledWrapped("OpenSCAD's export of the .scad: where a node cannot be traced back to one call in the .scad, "
                        "messages and the tree name its line here");
    }
    noteOverflow("CSG export");

    if (unfoldExport_) ImGui::SetNextItemOpen(true);
    unfoldExport_ = false;
    if (ImGui::CollapsingHeader("export")) {
        if (exportPath_.empty()) exportPath_ = defaultExportPath();
        char buffer[1024];
        std::snprintf(buffer, sizeof buffer, "%s", exportPath_.c_str());
        ImGui::SetNextItemWidth(-1);
        if (ImGui::InputText("##export", buffer, sizeof buffer)) exportPath_ = buffer;
        if (exporter_.busy()) {
            ImGui::TextWrapped("exporting... %s", exporter_.progressText().c_str());
            if (ImGui::SmallButton("cancel export (Esc)")) exporter_.cancel();
        } else if (ImGui::Button("export (Ctrl+E)")) {
            startExport(exportPath_);
        }
        ImGui::Checkbox("exact (CGAL)", &exportExact_);
        if (!exportExact_) {
            // Beside the box where a field of a few digits, its two step
            // buttons and its label fit; the field takes what they leave.
            const ImGuiStyle& style = ImGui::GetStyle();
            const float label = ImGui::CalcTextSize("cells").x + style.ItemInnerSpacing.x;
            nextInRow(ImGui::CalcTextSize("00000").x + 2 * style.FramePadding.x +
                      2 * (ImGui::GetFrameHeight() + style.ItemInnerSpacing.x) + label);
            ImGui::SetNextItemWidth(-label);
            if (ImGui::InputInt("cells", &exportResolution_, 64, 256)) {
                exportResolution_ = std::clamp(exportResolution_, remesh::kLeastResolution, remesh::kMostResolution);
            }
        }
        const std::string meshes = io::extensionList(io::ExportKind::Mesh);
        disabledWrapped(exportExact_ ? meshes + " (a 2D model: " + io::extensionList(io::ExportKind::Drawing) +
                                           "); evaluated by CGAL as OpenSCAD's render"
                                     : meshes + "; the result sampled on a grid of this many cells along its longest "
                                                "side, sharp edges kept");
    }
    noteOverflow("export");

    if (ImGui::CollapsingHeader("render", ImGuiTreeNodeFlags_DefaultOpen)) {
        bool autoLayers = settings_.layers == 0;
        if (ImGui::Checkbox("auto layers", &autoLayers)) autoLayers ? setLayers(0) : changeLayers(0);
        if (!autoLayers) {
            nextInRow(100 + ImGui::GetStyle().ItemInnerSpacing.x + ImGui::CalcTextSize("layers").x);
            int layers = settings_.layers;
            ImGui::SetNextItemWidth(100);
            if (ImGui::InputInt("layers", &layers)) setLayers(std::max(1, layers));
        }
        const std::string scheme = settings_.colorScheme;
        ImGui::SetNextItemWidth(std::min(ImGui::CalcItemWidth(), ImGui::GetContentRegionAvail().x -
                                                                     ImGui::GetStyle().ItemInnerSpacing.x -
                                                                     ImGui::CalcTextSize("colours").x));
        if (ImGui::BeginCombo("colours", scheme.c_str())) {
            for (const std::string& name : render::colorSchemeNames())
                if (ImGui::Selectable(name.c_str(), name == scheme)) {
                    settings_.colorScheme = name;
                    viewDirty_ = true;
                }
            ImGui::EndCombo();
        }
        int light = static_cast<int>(settings_.lighting);
        ImGui::TextUnformatted("light");
        nextInRow("strata", true);
        if (ImGui::RadioButton("strata", &light, static_cast<int>(render::Lighting::Strata))) {
            settings_.lighting = render::Lighting::Strata;
            viewDirty_ = true;
        }
        nextInRow("OpenSCAD", true);
        if (ImGui::RadioButton("OpenSCAD", &light, static_cast<int>(render::Lighting::OpenScad))) {
            settings_.lighting = render::Lighting::OpenScad;
            viewDirty_ = true;
        }
        nextInRow("outline", true);
        if (ImGui::Checkbox("outline", &settings_.outline)) viewDirty_ = true;
        int debug = static_cast<int>(debugView_);
        for (int k = 0; k < static_cast<int>(kDebugNames.size()); ++k) {
            if (k != 0) nextInRow(kDebugNames[static_cast<std::size_t>(k)], true);
            if (ImGui::RadioButton(kDebugNames[static_cast<std::size_t>(k)], &debug, k))
                setDebugView(static_cast<DebugView>(k));
        }
    }
    noteOverflow("render");

    if (ImGui::CollapsingHeader("frame", ImGuiTreeNodeFlags_DefaultOpen)) {
        int used = 0;
        for (int l : stats_.layersPerLeaf) used = std::max(used, l);
        if (stats_.plain) {
            wrappedAtSpaces(formatted("%.1f ms (plain %.1f, shade %.1f, copy %.1f)", stats_.totalMs, stats_.plainMs,
                                      stats_.shadeMs, stats_.readbackMs));
        } else {
            wrappedAtSpaces(formatted("%.1f ms (peel %.1f, evaluate %.1f, normal %.1f, shade %.1f, copy %.1f)",
                                      stats_.totalMs, stats_.peelMs, stats_.evaluateMs, stats_.normalMs,
                                      stats_.shadeMs, stats_.readbackMs));
        }
        wrappedAtSpaces(formatted("layers %s, used up to %d; %d operands", settings_.layers == 0 ? "auto" : "fixed",
                                  used, stats_.operands));
        wrappedAtSpaces(formatted("%d x %d px, %.1f MiB of layers, %d tile(s)", target_.width(), target_.height(),
                                  stats_.textureBytes / (1024.0 * 1024.0), stats_.tiles));
        if (stats_.unresolvedPixels > 0) ImGui::Text("%zu unresolved pixels", stats_.unresolvedPixels);
        for (const std::string& note : stats_.notes) ImGui::TextWrapped("%s", note.c_str());
    }
    noteOverflow("frame");

    if (ImGui::CollapsingHeader("camera", ImGuiTreeNodeFlags_DefaultOpen)) {
        wrappedAtSpaces(wrappableCamera(cameraLine()));
        if (ImGui::Button("copy --camera=")) copyCamera();
        // Where the screenshot goes: the name typed here, or the next
        // strata-view-N.png in the current folder when it is left empty.
        char shot[1024];
        std::snprintf(shot, sizeof shot, "%s", screenshotPath_.c_str());
        ImGui::SetNextItemWidth(-1);
        if (ImGui::InputTextWithHint("##screenshot", "strata-view-N.png", shot, sizeof shot)) screenshotPath_ = shot;
        if (ImGui::Button("screenshot (Ctrl+S)")) saveChosenScreenshot();
        if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
    }
    noteOverflow("camera");

    if (ImGui::CollapsingHeader("tree", ImGuiTreeNodeFlags_DefaultOpen)) drawTreePanel();
    noteOverflow("tree");
    panelOverflow_ = overflowThisFrame_;
    ImGui::End();
}

// Notes the first section of the frame whose items reach past where the
// window being drawn (the panel, or a scrolled box inside it) clips them on
// the right: text that the panel cuts.
void Viewer::noteOverflow(const char* section) {
    const ImGuiWindow* window = ImGui::GetCurrentWindow();
    const float over = window->DC.CursorMaxPos.x - window->InnerClipRect.Max.x;
    if (over > 0.5f && overflowThisFrame_.empty())
        overflowThisFrame_ = formatted("%s passes the panel's right edge by %.0f px", section, over);
}

void Viewer::drawTreePanel() {
    ImGui::TextDisabled("shown / # highlight / node");
    // A clipper: a tree of a million leaves lists only the rows on screen.
    // Rows under a hidden node show unticked and greyed: hiding the parent hides them.
    std::vector<bool> hiddenAbove(rows_.size(), false);
    std::vector<int> hiddenDepths;
    for (std::size_t k = 0; k < rows_.size(); ++k) {
        while (!hiddenDepths.empty() && hiddenDepths.back() >= rows_[k].depth) hiddenDepths.pop_back();
        hiddenAbove[k] = !hiddenDepths.empty();
        if (edits_.hidden.contains(rows_[k].node)) hiddenDepths.push_back(rows_[k].depth);
    }
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(rows_.size()));
    while (clipper.Step()) {
        for (int k = clipper.DisplayStart; k < clipper.DisplayEnd; ++k) {
            const TreeRow& row = rows_[static_cast<std::size_t>(k)];
            ImGui::PushID(row.node);
            const bool underHidden = hiddenAbove[static_cast<std::size_t>(k)];
            bool shown = !edits_.hidden.contains(row.node) && !underHidden;
            ImGui::BeginDisabled(underHidden);
            if (ImGui::Checkbox("##shown", &shown)) toggleHidden(row.node);
            ImGui::EndDisabled();
            ImGui::SameLine();
            // A '#' written in the file shows ticked; the box cannot take it away.
            const scene::Node& node = scene_.tree.nodes[static_cast<std::size_t>(row.node)];
            const bool sourceHighlight = node.kind == scene::NodeKind::Leaf &&
                                         scene_.tree.leaves[static_cast<std::size_t>(node.leaf)].display ==
                                             scene::Display::Highlight;
            bool highlighted = sourceHighlight || edits_.highlighted.contains(row.node);
            ImGui::BeginDisabled(sourceHighlight);
            if (ImGui::Checkbox("##highlight", &highlighted)) toggleHighlight(row.node);
            ImGui::EndDisabled();
            ImGui::SameLine();
            ImGui::SetCursorPosX(ImGui::GetCursorPosX() + 12.0f * static_cast<float>(row.depth));
            const std::string text = (row.background ? "% " : "") + std::to_string(row.node) + " " + row.label + rowLineNote(row.node);
            const std::string fitted = ellipsized(text, ImGui::GetContentRegionAvail().x);
            ImGui::TextUnformatted(fitted.c_str());
            if (fitted != text && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text.c_str());
            ImGui::PopID();
        }
    }
}

void Viewer::drawOpenPanel() {
    namespace fs = std::filesystem;
    if (focusOpen_) ImGui::SetNextItemOpen(true);
    if (!ImGui::CollapsingHeader("open (Ctrl+O)")) {
        focusOpen_ = false;
        return;
    }
    std::error_code ec;
    if (openPath_.empty()) {
        const fs::path folder = fs::path(path_).parent_path();  // as the file was named
        openPath_ = folder.empty() ? std::string("./") : folder.string() + "/";
    }
    char field[1024];
    std::snprintf(field, sizeof field, "%s", openPath_.c_str());
    ImGui::SetNextItemWidth(-1);
    if (focusOpen_) {
        ImGui::SetKeyboardFocusHere();
        focusOpen_ = false;
    }
    const bool entered = ImGui::InputTextWithHint("##open", "a .scad, .csg or mesh file, or a folder", field, sizeof field,
                                                  ImGuiInputTextFlags_EnterReturnsTrue);
    openPath_ = field;
    const bool isFile = fs::is_regular_file(openPath_, ec);
    ImGui::BeginDisabled(!isFile);
    const bool clicked = ImGui::Button("open");
    ImGui::EndDisabled();
    if (isFile && (entered || clicked)) openFile(openPath_);

    // The folder of the field: its subfolders and the files strata opens;
    // after a partial name, those that begin with it.
    const bool isFolder = fs::is_directory(openPath_, ec);
    const fs::path folder = isFolder ? fs::path(openPath_) : fs::path(openPath_).parent_path();
    const std::string prefix = isFolder ? std::string() : fs::path(openPath_).filename().string();
    const auto now = std::chrono::steady_clock::now();
    if (folder.string() != listedFolder_ || now - listedAt_ > std::chrono::seconds(2)) {
        listedFolder_ = folder.string();
        listedAt_ = now;
        listed_.clear();
        for (fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, fs::directory_options::skip_permission_denied, ec), end;
             !ec && it != end && listed_.size() < 500; it.increment(ec)) {
            const std::string name = it->path().filename().string();
            if (name.empty() || name.front() == '.') continue;
            const bool sub = it->is_directory(ec);
            if (sub || scene::isSceneExtension(lowerExtension(name))) listed_.push_back({name, sub});
        }
        std::sort(listed_.begin(), listed_.end(),
                  [](const FolderEntry& a, const FolderEntry& b) { return a.folder != b.folder ? a.folder : a.name < b.name; });
        if (fs::absolute(folder, ec).has_relative_path()) listed_.insert(listed_.begin(), {"..", true});
    }
    ImGui::BeginChild("open files", ImVec2(0, 120), true);
    for (const FolderEntry& entry : listed_) {
        if (!prefix.empty() && entry.name.rfind(prefix, 0) != 0) continue;
        const std::string name = entry.folder ? entry.name + "/" : entry.name;
        const std::string label = ellipsized(name, ImGui::GetContentRegionAvail().x);
        const bool chosen = ImGui::Selectable((label + "##" + name).c_str());
        if (label != name && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", name.c_str());
        if (!chosen) continue;
        if (entry.name == "..") {
            fs::path here = fs::absolute(folder, ec).lexically_normal();
            if (here.filename().empty()) here = here.parent_path();  // "a/b/" names b
            const fs::path up = here.parent_path();
            openPath_ = up.string() + (up.string().ends_with('/') ? "" : "/");
        } else if (entry.folder) {
            openPath_ = (folder / entry.name).string() + "/";
        } else {
            openPath_ = (folder / entry.name).string();
            openFile(openPath_);
        }
    }
    noteOverflow("open");
    ImGui::EndChild();

    if (recent_.files().empty()) return;
    disabledWrapped("recent");
    for (const std::string& file : recent_.files()) {
        const bool there = fs::is_regular_file(file, ec);
        const fs::path p(file);
        const std::string label = ellipsized(p.filename().string() + "  (" + p.parent_path().filename().string() + ")" +
                                                 (there ? "" : ", gone"),
                                             ImGui::GetContentRegionAvail().x);
        ImGui::BeginDisabled(!there);
        const bool chosen = ImGui::Selectable((label + "##" + file).c_str());
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", file.c_str());
        if (chosen) openFile(file);
    }
}

std::string Viewer::rowLineNote(int node) const {
    const SourceLocation& where = scene_.tree.nodes[static_cast<std::size_t>(node)].where;
    if (where.line <= 0) return {};
    // A .scad's node is positioned in the .scad (or a file it uses) where it
    // traces back to one call there, else in OpenSCAD's CSG export of it.
    const std::string line = std::to_string(where.line);
    if (scene_.csgExport.empty() || where.file == path_) return " (line " + line + ")";
    if (where.file == path_ + " (CSG export)") return " (CSG line " + line + ")";
    return " (" + std::filesystem::path(where.file).filename().string() + " line " + line + ")";
}

void Viewer::drawPeelLabels() {
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
    // Over the view only: never over the panel.
    const float left = static_cast<float>(viewLeft()) / scale.x;
    draw->PushClipRect(ImVec2(viewLeftInWindow(), 0.0f), ImGui::GetIO().DisplaySize, false);
    for (const PeelTile& tile : peelTiles_) {
        std::string label =
            "leaf " + std::to_string(tile.leaf) + " L" + std::to_string(tile.layer) + (tile.far ? " far" : " near");
        // Small tiles get the leaf number only, on the operand's first tile.
        if (ImGui::CalcTextSize(label.c_str()).x > tile.w / scale.x - 4) {
            if (tile.layer != 0 || tile.far) continue;
            label = std::to_string(tile.leaf);
        }
        draw->AddText(ImVec2(left + tile.x / scale.x + 3, tile.y / scale.y + 2), IM_COL32(255, 220, 120, 255),
                      label.c_str());
    }
    draw->PopClipRect();
}

}  // namespace strata::view
