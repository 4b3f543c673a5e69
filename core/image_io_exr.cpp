// OpenEXR reading/writing. The only translation unit that includes OpenEXR.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <map>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/image_io.h"

namespace dp::core {

namespace {
std::string channel_name(const std::string& layer, const char* c) {
  return layer.empty() ? std::string(c) : layer + "." + c;
}
}  // namespace

void write_exr(const std::string& path, const std::vector<NamedLayer>& layers) {
  if (layers.empty()) throw IoError("no layers to write", path);
  const int w = layers[0].image.width(), h = layers[0].image.height();
  for (const auto& l : layers)
    if (l.image.width() != w || l.image.height() != h)
      throw IoError("layer '" + l.name + "' has a different size", path);
  try {
    Imf::Header header(w, h);
    Imf::FrameBuffer fb;
    const char* comps[3] = {"R", "G", "B"};
    for (const auto& l : layers) {
      char* base = reinterpret_cast<char*>(const_cast<Rgb*>(l.image.pixels().data()));
      for (int c = 0; c < 3; ++c) {
        const std::string name = channel_name(l.name, comps[c]);
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        fb.insert(name, Imf::Slice(Imf::FLOAT, base + c * sizeof(float), sizeof(Rgb), sizeof(Rgb) * size_t(w)));
      }
    }
    // The file is closed (OutputFile's destructor) before write_atomically renames it.
    write_atomically(path, [&](const std::string& tmp) {
      Imf::OutputFile file(tmp.c_str(), header);
      file.setFrameBuffer(fb);
      file.writePixels(h);
    });
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(std::string("cannot write EXR: ") + e.what(), path);
  }
}

void write_exr(const std::string& path, const Image& image) { write_exr(path, {NamedLayer{"", image}}); }

std::vector<NamedLayer> read_exr_layers(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    // Group channels "<layer>.<C>" (or "<C>") by layer.
    std::map<std::string, std::map<char, std::string>> groups;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
      const std::string name = it.name();
      const size_t dot = name.rfind('.');
      const std::string layer = dot == std::string::npos ? "" : name.substr(0, dot);
      const std::string comp = dot == std::string::npos ? name : name.substr(dot + 1);
      if (comp == "R" || comp == "G" || comp == "B" || comp == "Y") groups[layer][comp[0]] = name;
    }
    if (groups.empty()) {
      const bool raw = file.header().findTypedAttribute<Imf::StringAttribute>("deltapath.format") != nullptr;
      throw IoError(raw ? "a `render --partial` file holds raw sums, not an image: `deltapath merge` it first"
                        : "EXR has no R/G/B or Y channels",
                    path);
    }
    std::vector<NamedLayer> layers;
    layers.reserve(groups.size());
    Imf::FrameBuffer fb;
    for (const auto& [layer, comps] : groups) {
      layers.push_back(NamedLayer{layer, Image(w, h)});
      Image& img = layers.back().image;
      char* base = reinterpret_cast<char*>(img.pixels().data()) -
                   (size_t(dw.min.x) + size_t(dw.min.y) * size_t(w)) * sizeof(Rgb);
      const char order[3] = {'R', 'G', 'B'};
      for (int c = 0; c < 3; ++c) {
        auto it = comps.find(order[c]);
        if (it == comps.end()) it = comps.find('Y');
        if (it == comps.end()) it = comps.begin();
        fb.insert(it->second, Imf::Slice(Imf::FLOAT, base + c * sizeof(float), sizeof(Rgb), sizeof(Rgb) * size_t(w)));
      }
    }
    // A channel can only be bound once per framebuffer; re-read for duplicated bindings.
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    for (auto& l : layers) {
      const auto& comps = groups[l.name];
      if (comps.size() == 1 || (comps.count('Y') && !comps.count('R')))
        for (auto& p : l.image.pixels()) p = Rgb::Constant(p[0]);
    }
    if (layers.size() > 1) {
      // "RGB" is a common alias for the main layer.
      for (auto& l : layers)
        if (l.name == "RGB") l.name.clear();
    }
    return layers;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(std::string("cannot read EXR: ") + e.what(), path);
  }
}

Image read_exr(const std::string& path) {
  auto layers = read_exr_layers(path);
  for (auto& l : layers)
    if (l.name.empty()) return std::move(l.image);
  if (layers.size() == 1) return std::move(layers[0].image);
  throw IoError("EXR has no main RGB layer (layers are named; pick one)", path);
}

}  // namespace dp::core
