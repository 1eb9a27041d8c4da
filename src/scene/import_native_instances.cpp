// Instancing in the native format: named objects ("objects") placed by shapes
// of type "instance" (docs/scene-format.md, "Instancing").
#include <string>
#include <utility>
#include <vector>

#include "scene/import_transform.h"
#include "scene/native_shapes.h"
#include "scene/suggest.h"

namespace pt {

bool is_instance(const JsonValue& v) {
  const JsonValue* type = v.is_object() ? v.find("type") : nullptr;
  return type && type->is_string() && type->as_string() == "instance";
}

void read_native_objects(ImportContext& ctx, const JsonValue& v, std::vector<NativeMaterial>& materials,
                         std::vector<std::vector<int>>& object_material) {
  if (!expect_array(ctx.read, v, "objects")) return;
  for (std::size_t i = 0; i < v.as_array().size(); ++i) {
    const JsonValue& o = v.as_array()[i];
    if (!expect_object(ctx.read, o, "objects[" + std::to_string(i) + "]")) continue;
    ObjectReader r(ctx.read, o, "object");
    ObjectDesc object;
    object.where = r.where();
    Sourced<std::string> name;
    r.read_required("name", name);
    object.name = name.value;
    for (const ObjectDesc& other : ctx.scene.objects) {
      if (other.name == object.name && r.ok()) {
        ctx.diag().error(name.where, "an object named '" + object.name + "' is already defined");
        r.fail();
      }
    }
    const JsonValue* shapes = r.require("shapes");
    r.finish();
    if (!r.ok() || !shapes || !expect_array(ctx.read, *shapes, "shapes")) continue;
    // The object's shapes are read as top-level shapes are, then moved into it.
    std::vector<ShapeDesc> top = std::exchange(ctx.scene.shapes, {});
    std::vector<int> material;
    for (std::size_t k = 0; k < shapes->as_array().size(); ++k) {
      const JsonValue& s = shapes->as_array()[k];
      if (is_instance(s)) {
        ctx.diag().error(ctx.read.at(s), "an object cannot place instances (one level of instancing)");
        continue;
      }
      read_native_shape(ctx, s, k, materials, material);
    }
    object.shapes = std::exchange(ctx.scene.shapes, std::move(top));
    ctx.scene.objects.push_back(std::move(object));
    object_material.push_back(std::move(material));
  }
}

void read_native_instance(ImportContext& ctx, const JsonValue& v, std::vector<NativeMaterial>& materials) {
  ObjectReader r(ctx.read, v, "instance");
  r.get("type");
  InstanceDesc inst;
  inst.where = r.where();
  Sourced<std::string> name;
  r.read_required("object", name);
  const int material = resolve_material(ctx, r, materials);
  if (material == -2) r.fail();
  if (material >= 0) inst.material = material;
  if (const JsonValue* t = r.get("transform"); t && !read_transform(ctx.read, *t, inst.transform)) r.fail();
  Sourced<std::string> label;
  r.read("name", label);
  inst.name = label.value;
  r.finish();
  if (!r.ok()) return;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < ctx.scene.objects.size(); ++i) {
    if (ctx.scene.objects[i].name == name.value) {
      inst.object = static_cast<int>(i);
      ctx.scene.instances.push_back(std::move(inst));
      return;
    }
    names.push_back(ctx.scene.objects[i].name);
  }
  std::string message = "unknown object '" + name.value + "'";
  message += did_you_mean(name.value, names,
                          names.empty() ? "; the scene defines no objects (top-level \"objects\")"
                                        : "; the scene defines " + quoted_list(names, "and"));
  ctx.diag().error(name.where, std::move(message));
}

void warn_unplaced_objects(ImportContext& ctx) {
  std::vector<bool> placed(ctx.scene.objects.size(), false);
  for (const InstanceDesc& inst : ctx.scene.instances)
    if (inst.object >= 0) placed[static_cast<std::size_t>(inst.object)] = true;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    const ObjectDesc& o = ctx.scene.objects[i];
    if (!placed[i])
      ctx.diag().warning(o.where, "object '" + o.name + "' is not placed by any instance (a shape of type " +
                                      "\"instance\" with \"object\": \"" + o.name + "\"); it will not be visible");
  }
}

}  // namespace pt
